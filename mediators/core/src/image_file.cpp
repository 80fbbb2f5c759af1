#include "tsr/med/image_file.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <span>

#include "tsr/imageio/image_codec.hpp"
#include "tsr/med/file_replacement.hpp"

namespace tsr::med {

namespace {
bool isFloatFormat(const std::string& path) {
  std::string ext = path.substr(path.find_last_of('.') + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext == "exr" || ext == "pfm" || ext == "hdr" || ext == "tif" || ext == "tiff";
}

std::uint8_t encodeSrgb(float linear) {
  float c = std::clamp(linear, 0.0f, 1.0f);
  float s = c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
  return static_cast<std::uint8_t>(std::lround(s * 255.0f));
}

// Opaque RGB, clamped and sRGB-encoded: what an 8-bit picture holds.
std::vector<std::uint8_t> srgbBytes(const std::vector<glm::vec4>& pixels) {
  std::vector<std::uint8_t> data;
  data.reserve(pixels.size() * 3);
  for (const auto& p : pixels)
    for (int c = 0; c < 3; ++c) data.push_back(encodeSrgb(p[c]));
  return data;
}

float decodeSrgb(float s) { return s <= 0.04045f ? s / 12.92f : std::pow((s + 0.055f) / 1.055f, 2.4f); }

std::vector<glm::vec4> pixelsOf(const FrameBuffer& fb, const std::string& output) {
  if (isColourOutput(output)) return fb.colour;
  if (isDepthOutput(output)) {
    std::vector<glm::vec4> d(fb.depth.size());
    for (std::size_t i = 0; i < d.size(); ++i) {
      float z = std::isfinite(fb.depth[i]) ? fb.depth[i] : 0.0f;
      d[i] = glm::vec4(z, z, z, 1.0f);
    }
    return d;
  }
  auto it = fb.outputs.find(output);
  if (it == fb.outputs.end()) {
    std::string known = "colour, depth";
    for (const auto& [name, px] : fb.outputs) known += ", " + name;
    throw ImageFileError("no output '" + output + "' (available: " + known + ")");
  }
  return it->second;
}

template <class T>
std::span<const std::byte> bytesOf(const std::vector<T>& v) {
  return std::as_bytes(std::span(v));
}

// Runs an image codec call; its errors become ImageFileError.
template <class F>
auto coded(F&& f) {
  try {
    return f();
  } catch (const imageio::CodecError& e) {
    throw ImageFileError(e.what());
  }
}

imageio::Layout layoutOf(const FrameBuffer& fb, std::uint32_t channels, imageio::Sample sample) {
  imageio::Layout l;
  l.width = fb.width, l.height = fb.height, l.channels = channels, l.sample = sample;
  return l;
}

// Writes `path` in the format `named` (the final name) says.
void writeImageFile(const std::string& path, const std::string& named, const FrameBuffer& fb,
                    const std::vector<glm::vec4>& pixels) {
  const bool floats = isFloatFormat(named);
  // Float formats keep alpha; 8-bit ones are viewed as pictures, so opaque RGB.
  const std::uint32_t channels =
      floats && named.find(".pfm") == std::string::npos && named.find(".hdr") == std::string::npos ? 4 : 3;
  coded([&] {
    if (!floats)
      return imageio::writeFile(path, named, layoutOf(fb, channels, imageio::Sample::UInt8),
                                bytesOf(srgbBytes(pixels)));
    std::vector<float> data;
    data.reserve(pixels.size() * channels);
    for (const auto& p : pixels)
      for (std::uint32_t c = 0; c < channels; ++c) data.push_back(p[int(c)]);
    imageio::writeFile(path, named, layoutOf(fb, channels, imageio::Sample::Float), bytesOf(data));
  });
}
}  // namespace

void writeLayeredExr(const std::string& path, const FrameBuffer& fb) {
  if (fb.width == 0 || fb.height == 0) throw ImageFileError(path + ": empty image");
  if (path.size() < 4 || path.compare(path.size() - 4, 4, ".exr") != 0)
    throw ImageFileError(path + ": layered images are written as .exr only");
  std::vector<std::string> names{"R", "G", "B", "A", "Z"};
  for (const auto& [name, pixels] : fb.outputs)
    for (const char* c : {".R", ".G", ".B"}) names.push_back(name + c);
  const std::size_t channels = names.size(), count = std::size_t{fb.width} * fb.height;
  std::vector<float> data(count * channels);
  for (std::size_t i = 0; i < count; ++i) {
    float* px = &data[i * channels];
    for (int c = 0; c < 4; ++c) px[c] = fb.colour[i][c];
    px[4] = fb.depth[i];
    std::size_t at = 5;
    for (const auto& [name, pixels] : fb.outputs) {
      const glm::vec4 v = i < pixels.size() ? pixels[i] : glm::vec4(0.0f);
      for (int c = 0; c < 3; ++c) px[at++] = v[c];
    }
  }
  imageio::Layout layout = layoutOf(fb, std::uint32_t(channels), imageio::Sample::Float);
  layout.channelNames = names;
  layout.alphaChannel = 3;
  layout.depthChannel = 4;
  replaceFile(path, [&](const std::string& temporary) {
    coded([&] { imageio::writeFile(temporary, path, layout, bytesOf(data)); });
  });
}

void writeImage(const std::string& path, const FrameBuffer& fb, const std::string& output,
                const DisplayTransform& display) {
  if (fb.width == 0 || fb.height == 0) throw ImageFileError(path + ": empty image");
  auto pixels = pixelsOf(fb, output);
  const bool radiance = isColourOutput(output) || output == "direct" || output == "indirect";
  if (radiance && !display.identity() && !isFloatFormat(path))
    for (auto& p : pixels) p = display.apply(p);
  // A failed or interrupted write leaves an existing image as it was.
  replaceFile(path, [&](const std::string& temporary) { writeImageFile(temporary, path, fb, pixels); });
}

std::vector<std::uint8_t> encodePng(const FrameBuffer& fb, const DisplayTransform& display) {
  if (fb.width == 0 || fb.height == 0) throw ImageFileError("cannot encode an empty image");
  std::vector<glm::vec4> pixels = fb.colour;
  if (!display.identity())
    for (auto& p : pixels) p = display.apply(p);
  imageio::Layout layout = layoutOf(fb, 3, imageio::Sample::UInt8);
  layout.pngCompression = 3;  // streamed frames: speed over the last few percent
  return coded([&] { return imageio::encode("frame.png", layout, bytesOf(srgbBytes(pixels))); });
}

FrameBuffer readImage(const std::string& path) {
  const imageio::Image image = coded([&] { return imageio::readFile(path, imageio::Sample::Float); });
  const int channels = int(image.channels);
  FrameBuffer fb(image.width, image.height);
  for (std::size_t i = 0; i < fb.colour.size(); ++i) {
    glm::vec4 p(0, 0, 0, 1);
    for (int c = 0; c < std::min(channels, 4); ++c) {
      float v = image.floats[i * std::size_t(channels) + std::size_t(c)];
      p[c] = (image.floatingPoint || c == 3) ? v : decodeSrgb(v);
    }
    if (channels == 1) p = glm::vec4(p.r, p.r, p.r, 1);
    fb.colour[i] = p;
  }
  return fb;
}

}  // namespace tsr::med
