#pragma once
// What the OpenImageIO module (oiio_codec.cpp) offers the loader
// (image_codec.cpp): one table of functions, found by its entry point's
// name, which carries the table's version. Both sides are built by the same
// compiler in the same build, so C++ types cross; exceptions do not (each
// function returns an error text, empty on success).
#include "tsr/imageio/image_codec.hpp"

namespace tsr::imageio::detail {

struct CodecTable {
  std::string (*writeFile)(const std::string& path, const std::string& formatName, const Layout& layout,
                           std::span<const std::byte> pixels);
  std::string (*encode)(const std::string& formatName, const Layout& layout, std::span<const std::byte> pixels,
                        std::vector<std::uint8_t>& out);
  std::string (*readFile)(const std::string& path, Sample as, Image& out);
  std::string (*decode)(std::span<const std::uint8_t> encoded, const std::string& formatName, std::uint64_t maxPixels,
                        Image& out);
};

}  // namespace tsr::imageio::detail

// The module's one exported symbol.
#define TSR_IMAGEIO_ENTRY "tsr_imageio_codec_table_v1"
