#include "images/image_decoding.hpp"

#include <cstring>

#include "images/png_structure.hpp"
#include "tsr/imageio/image_codec.hpp"
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

  imageio::Image decoded;
  try {
    decoded = imageio::decode(bytes, name, maxPixels);
  } catch (const imageio::CodecError& e) {
    throw ImportError(source, what + " " + e.what());
  }
  parsed::Image img;
  img.width = decoded.width;
  img.height = decoded.height;
  img.channels = decoded.channels;
  img.pixels = std::move(decoded.bytes);
  return img;
}

}  // namespace tsr::sg
