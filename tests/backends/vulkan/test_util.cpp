#include "test_util.hpp"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>
#pragma GCC diagnostic pop

#include <vector>

namespace tsr::vk::test {

void writePng(const std::string& path, const FrameBuffer& fb, float exposure) {
  std::vector<unsigned char> rgb(std::size_t(fb.width()) * fb.height() * 3);
  for (std::uint32_t y = 0; y < fb.height(); ++y)
    for (std::uint32_t x = 0; x < fb.width(); ++x)
      for (int c = 0; c < 3; ++c) {
        float v = std::clamp(fb.colour(x, y)[c] * exposure, 0.0f, 1.0f);
        v = v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
        rgb[(std::size_t(y) * fb.width() + x) * 3 + c] = static_cast<unsigned char>(v * 255.0f + 0.5f);
      }
  stbi_write_png(path.c_str(), int(fb.width()), int(fb.height()), 3, rgb.data(), int(fb.width()) * 3);
}

}  // namespace tsr::vk::test
