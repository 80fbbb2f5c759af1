#include "tsr/med/image_file.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

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

// Writes `path` in the format `named` (the final name) says.
void writeImageFile(const std::string& path, const std::string& named, const FrameBuffer& fb,
                    const std::vector<glm::vec4>& pixels) {
  auto file = OIIO::ImageOutput::create(named);
  if (!file) throw ImageFileError(named + ": " + OIIO::geterror());
  bool floats = isFloatFormat(named);
  // Float formats keep alpha; 8-bit ones are viewed as pictures, so opaque RGB.
  int channels = floats && named.find(".pfm") == std::string::npos && named.find(".hdr") == std::string::npos ? 4 : 3;
  OIIO::ImageSpec spec(static_cast<int>(fb.width), static_cast<int>(fb.height), channels,
                       floats ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
  if (!file->open(path, spec)) throw ImageFileError(named + ": " + file->geterror());
  bool ok;
  if (floats) {
    std::vector<float> data;
    data.reserve(pixels.size() * channels);
    for (const auto& p : pixels)
      for (int c = 0; c < channels; ++c) data.push_back(p[c]);
    ok = file->write_image(OIIO::TypeDesc::FLOAT, data.data());
  } else {
    ok = file->write_image(OIIO::TypeDesc::UINT8, srgbBytes(pixels).data());
  }
  if (!ok || !file->close()) throw ImageFileError(named + ": " + file->geterror());
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
  replaceFile(path, [&](const std::string& temporary) {
    auto file = OIIO::ImageOutput::create(path);
    if (!file) throw ImageFileError(path + ": " + OIIO::geterror());
    OIIO::ImageSpec spec(static_cast<int>(fb.width), static_cast<int>(fb.height), static_cast<int>(channels),
                         OIIO::TypeDesc::FLOAT);
    spec.channelnames = names;
    spec.alpha_channel = 3;
    spec.z_channel = 4;
    if (!file->open(temporary, spec)) throw ImageFileError(path + ": " + file->geterror());
    if (!file->write_image(OIIO::TypeDesc::FLOAT, data.data()) || !file->close())
      throw ImageFileError(path + ": " + file->geterror());
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
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput memory(bytes);
  auto file = OIIO::ImageOutput::create("frame.png", &memory);
  if (!file) throw ImageFileError("png: " + OIIO::geterror());
  OIIO::ImageSpec spec(static_cast<int>(fb.width), static_cast<int>(fb.height), 3, OIIO::TypeDesc::UINT8);
  spec.attribute("png:compressionLevel", 3);  // streamed frames: speed over the last few percent
  if (!file->open("frame.png", spec) || !file->write_image(OIIO::TypeDesc::UINT8, srgbBytes(pixels).data()) ||
      !file->close())
    throw ImageFileError("png: " + file->geterror());
  return {bytes.begin(), bytes.end()};
}

FrameBuffer readImage(const std::string& path) {
  auto file = OIIO::ImageInput::open(path);
  if (!file) throw ImageFileError(path + ": " + OIIO::geterror());
  const OIIO::ImageSpec& spec = file->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) throw ImageFileError(path + ": empty image");
  std::vector<float> data(std::size_t(spec.width) * spec.height * spec.nchannels);
  if (!file->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, data.data()))
    throw ImageFileError(path + ": " + file->geterror());
  bool linear = spec.format.is_floating_point();
  FrameBuffer fb(static_cast<std::uint32_t>(spec.width), static_cast<std::uint32_t>(spec.height));
  for (std::size_t i = 0; i < fb.colour.size(); ++i) {
    glm::vec4 p(0, 0, 0, 1);
    for (int c = 0; c < std::min(spec.nchannels, 4); ++c) {
      float v = data[i * spec.nchannels + c];
      p[c] = (linear || c == 3) ? v : decodeSrgb(v);
    }
    if (spec.nchannels == 1) p = glm::vec4(p.r, p.r, p.r, 1);
    fb.colour[i] = p;
  }
  return fb;
}

}  // namespace tsr::med
