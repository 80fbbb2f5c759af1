// Out-of-line members of the concrete container types.
#include <cstring>

#include <glm/gtc/matrix_transform.hpp>

#include "tsr/sg/camera.hpp"
#include "tsr/sg/geometry.hpp"
#include "tsr/sg/image.hpp"

namespace tsr::sg {

std::optional<std::string> Geometry::invalidReason() const {
  const auto& indices = indices_.get();
  const std::size_t per = indicesPerPrimitive(primitive_);
  if (indices.size() % per != 0)
    return "index count " + std::to_string(indices.size()) + " is not a multiple of " + std::to_string(per);
  for (std::size_t i = 0; i < indices.size(); ++i)
    if (indices[i] >= positions_.size())
      return "index " + std::to_string(indices[i]) + " at " + std::to_string(i) + " exceeds " +
             std::to_string(positions_.size()) + " vertices";
  auto attribute = [&](std::size_t n, const char* what) -> std::optional<std::string> {
    if (n != 0 && n != positions_.size())
      return std::string(what) + " count " + std::to_string(n) + " differs from " + std::to_string(positions_.size()) +
             " positions";
    return std::nullopt;
  };
  if (auto r = attribute(normals_.size(), "normal")) return r;
  if (auto r = attribute(uvs_.size(), "uv")) return r;
  if (auto r = attribute(colors_.size(), "colour")) return r;
  return std::nullopt;
}

std::size_t Image::expectedByteCount() const {
  std::size_t bytesPerChannel = format_ == PixelFormat::Float32 ? 4 : 1;
  return std::size_t{width_} * height_ * channels_ * bytesPerChannel;
}

void Image::setPixels(std::uint32_t width, std::uint32_t height, std::uint32_t channels, PixelFormat format,
                      std::vector<std::uint8_t> pixels) {
  if (channels < 1 || channels > 4) throw SceneError("Image: channels must be 1 to 4, not " + std::to_string(channels));
  std::size_t expected = std::size_t{width} * height * channels * (format == PixelFormat::Float32 ? 4 : 1);
  if (pixels.size() != expected)
    throw SceneError("Image: " + std::to_string(pixels.size()) + " bytes given for " + std::to_string(width) + "x" +
                     std::to_string(height) + "x" + std::to_string(channels) + ", expected " +
                     std::to_string(expected));
  if (format == PixelFormat::Float32) {
    for (std::size_t i = 0; i < pixels.size(); i += 4) {
      float v;
      std::memcpy(&v, pixels.data() + i, 4);
      if (!std::isfinite(v)) throw SceneError("Image: non-finite pixel value");
    }
  }
  set<&Image::width_>(width);
  set<&Image::height_>(height);
  set<&Image::channels_>(channels);
  set<&Image::format_>(format);
  set<&Image::pixels_>(std::move(pixels));
}

std::optional<std::string> Image::invalidReason() const {
  if (channels_ < 1 || channels_ > 4) return "channel count " + std::to_string(channels_) + " is not 1 to 4";
  if (pixels_.size() != expectedByteCount())
    return std::to_string(pixels_.size()) + " pixel bytes for " + std::to_string(width_) + "x" +
           std::to_string(height_) + "x" + std::to_string(channels_) + ", expected " +
           std::to_string(expectedByteCount());
  return std::nullopt;
}

void Camera::lookAt(const Vec3& eye, const Vec3& target, const Vec3& up) {
  setPose(glm::inverse(glm::lookAt(eye, target, up)));
}

}  // namespace tsr::sg
