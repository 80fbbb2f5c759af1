#include "image_decoding.hpp"

#include <cstring>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "png_structure.hpp"
#include "tsr/sg/import/import_error.hpp"

namespace tsr::sg {
namespace {

// The plugin is picked by file extension; the name is never opened because
// the bytes come through an IOProxy. Magic bytes beat the declared type.
std::string formatName(const std::vector<std::uint8_t>& b, const std::string& mimeType) {
  static const std::uint8_t png[] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
  if (b.size() >= sizeof(png) && std::memcmp(b.data(), png, sizeof(png)) == 0) return "memory.png";
  if (b.size() >= 3 && b[0] == 0xFF && b[1] == 0xD8 && b[2] == 0xFF) return "memory.jpg";
  if (mimeType == "image/png") return "memory.png";
  if (mimeType == "image/jpeg") return "memory.jpg";
  return {};
}

}  // namespace

parsed::Image decodeImage(const std::vector<std::uint8_t>& bytes, const std::string& mimeType, std::uint64_t maxPixels,
                          const std::string& source, const std::string& what) {
  if (bytes.empty()) throw ImportError(source, what + " has no data");
  const std::string name = formatName(bytes, mimeType);
  if (name.empty()) throw ImportError(source, what + " is neither PNG nor JPEG");
  if (name == "memory.png")
    if (const std::string problem = pngStructureProblem(bytes); !problem.empty())
      throw ImportError(source, what + " " + problem);

  OIIO::Filesystem::IOMemReader reader(bytes.data(), bytes.size());
  // glTF colours are straight (unassociated) alpha; keep them as stored.
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  // With a config, OpenImageIO takes the proxy from it, not from the argument.
  OIIO::Filesystem::IOProxy* proxy = &reader;
  config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
  auto input = OIIO::ImageInput::open(name, &config, &reader);
  if (!input) throw ImportError(source, what + " cannot be decoded: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = input->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 || spec.nchannels > 4)
    throw ImportError(source, what + " has an unsupported size or channel count");
  const std::uint64_t pixels = std::uint64_t(spec.width) * std::uint64_t(spec.height);
  if (pixels > maxPixels)
    throw ImportError(source, what + " has " + std::to_string(pixels) + " pixels, more than the limit of " +
                                  std::to_string(maxPixels));

  parsed::Image img;
  img.width = static_cast<std::uint32_t>(spec.width);
  img.height = static_cast<std::uint32_t>(spec.height);
  img.channels = static_cast<std::uint32_t>(spec.nchannels);
  img.pixels.resize(static_cast<std::size_t>(pixels) * img.channels);
  if (!input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, img.pixels.data()))
    throw ImportError(source, what + " cannot be decoded: " + input->geterror());
  input->close();
  return img;
}

}  // namespace tsr::sg
