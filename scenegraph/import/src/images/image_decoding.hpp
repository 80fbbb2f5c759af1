#pragma once
// Decodes PNG and JPEG bytes held in memory with OpenImageIO into 8-bit
// pixels; nothing touches the disk.
#include <cstdint>
#include <string>
#include <vector>

#include "parsed_scene.hpp"

namespace tsr::sg {

// Throws ImportError(source, "<what>: ...") for bytes it cannot decode or
// images with more than maxPixels pixels.
parsed::Image decodeImage(const std::vector<std::uint8_t>& bytes, const std::string& mimeType, std::uint64_t maxPixels,
                          const std::string& source, const std::string& what);

}  // namespace tsr::sg
