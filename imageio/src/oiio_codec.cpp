// The OpenImageIO module: the only code of ours that links OpenImageIO.
// Loaded on first use by image_codec.cpp (see image_codec.hpp for why).
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <exception>

#include "codec_table.hpp"

namespace tsr::imageio::detail {
namespace {

OIIO::TypeDesc typeOf(Sample s) { return s == Sample::Float ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8; }

std::size_t sampleSize(Sample s) { return s == Sample::Float ? sizeof(float) : 1; }

OIIO::ImageSpec specOf(const Layout& l) {
  OIIO::ImageSpec spec(int(l.width), int(l.height), int(l.channels), typeOf(l.sample));
  if (!l.channelNames.empty()) spec.channelnames = l.channelNames;
  if (l.alphaChannel >= 0) spec.alpha_channel = l.alphaChannel;
  if (l.depthChannel >= 0) spec.z_channel = l.depthChannel;
  if (l.pngCompression >= 0) spec.attribute("png:compressionLevel", l.pngCompression);
  if (l.straightAlpha) spec.attribute("oiio:UnassociatedAlpha", 1);
  return spec;
}

std::string checkLayout(const Layout& l, std::span<const std::byte> pixels) {
  if (l.width == 0 || l.height == 0 || l.channels == 0) return "empty image";
  if (!l.channelNames.empty() && l.channelNames.size() != l.channels) return "channel names do not match channels";
  const std::size_t want = std::size_t(l.width) * l.height * l.channels * sampleSize(l.sample);
  if (pixels.size() != want)
    return std::to_string(pixels.size()) + " bytes of pixels for a layout of " + std::to_string(want);
  return {};
}

// Writes through `file`, opened on `name` (a path, or a name for a proxy).
std::string writeThrough(OIIO::ImageOutput& file, const std::string& name, const Layout& l,
                         std::span<const std::byte> pixels) {
  if (!file.open(name, specOf(l))) return file.geterror();
  if (!file.write_image(typeOf(l.sample), pixels.data()) || !file.close()) return file.geterror();
  return {};
}

// Error texts of reading and decoding read on after the name of what was
// read ("has 5 channels, more than 4"); of writing, after a colon.
// Turns a C++ exception inside OpenImageIO into an error text.
template <class F>
std::string guarded(F&& f) {
  try {
    return f();
  } catch (const std::exception& e) {
    return e.what();
  } catch (...) {
    return "unknown error in OpenImageIO";
  }
}

std::string writeFile(const std::string& path, const std::string& formatName, const Layout& l,
                      std::span<const std::byte> pixels) {
  return guarded([&]() -> std::string {
    if (auto problem = checkLayout(l, pixels); !problem.empty()) return problem;
    auto file = OIIO::ImageOutput::create(formatName);
    if (!file) return OIIO::geterror();
    return writeThrough(*file, path, l, pixels);
  });
}

std::string encode(const std::string& formatName, const Layout& l, std::span<const std::byte> pixels,
                   std::vector<std::uint8_t>& out) {
  return guarded([&]() -> std::string {
    if (auto problem = checkLayout(l, pixels); !problem.empty()) return problem;
    std::vector<unsigned char> bytes;
    OIIO::Filesystem::IOVecOutput memory(bytes);
    auto file = OIIO::ImageOutput::create(formatName, &memory);
    if (!file) return OIIO::geterror();
    if (auto problem = writeThrough(*file, formatName, l, pixels); !problem.empty()) return problem;
    out.assign(bytes.begin(), bytes.end());
    return {};
  });
}

std::string readInto(OIIO::ImageInput& input, Sample as, std::uint64_t maxPixels, std::uint32_t maxChannels,
                     Image& out) {
  const OIIO::ImageSpec& spec = input.spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) return "is empty";
  if (std::uint32_t(spec.nchannels) > maxChannels)
    return "has " + std::to_string(spec.nchannels) + " channels, more than " + std::to_string(maxChannels);
  const std::uint64_t count = std::uint64_t(spec.width) * std::uint64_t(spec.height);
  if (count > maxPixels)
    return "has " + std::to_string(count) + " pixels, more than the limit of " + std::to_string(maxPixels);
  Image img;
  img.width = std::uint32_t(spec.width), img.height = std::uint32_t(spec.height);
  img.channels = std::uint32_t(spec.nchannels);
  img.floatingPoint = spec.format.is_floating_point();
  img.channelNames = spec.channelnames;
  const std::size_t values = std::size_t(count) * img.channels;
  void* data = nullptr;
  if (as == Sample::Float) {
    img.floats.resize(values);
    data = img.floats.data();
  } else {
    img.bytes.resize(values);
    data = img.bytes.data();
  }
  if (!input.read_image(0, 0, 0, spec.nchannels, typeOf(as), data)) return "cannot be decoded: " + input.geterror();
  input.close();
  out = std::move(img);
  return {};
}

std::string readFile(const std::string& path, Sample as, Image& out) {
  return guarded([&]() -> std::string {
    auto input = OIIO::ImageInput::open(path);
    if (!input) return "cannot be read: " + OIIO::geterror();
    return readInto(*input, as, ~std::uint64_t{0}, 1u << 16, out);
  });
}

std::string decode(std::span<const std::uint8_t> encoded, const std::string& formatName, std::uint64_t maxPixels,
                   Image& out) {
  return guarded([&]() -> std::string {
    OIIO::Filesystem::IOMemReader reader(encoded.data(), encoded.size());
    // glTF colours are straight (unassociated) alpha; keep them as stored.
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    // With a config, OpenImageIO takes the proxy from it, not from the argument.
    OIIO::Filesystem::IOProxy* proxy = &reader;
    config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    auto input = OIIO::ImageInput::open(formatName, &config, &reader);
    if (!input) return "cannot be decoded: " + OIIO::geterror();
    return readInto(*input, Sample::UInt8, maxPixels, 4, out);
  });
}

constexpr CodecTable kTable{writeFile, encode, readFile, decode};

}  // namespace
}  // namespace tsr::imageio::detail

extern "C" __attribute__((visibility("default"))) const tsr::imageio::detail::CodecTable* tsr_imageio_codec_table_v1() {
  return &tsr::imageio::detail::kTable;
}
