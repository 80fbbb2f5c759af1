#pragma once
// A walk over a PNG's chunks before any decoder sees it: signature, every
// chunk inside the bytes with a matching CRC, IHDR first, IEND last.
// libpng (under OpenImageIO) prints its own errors to stderr before failing,
// so a truncated or damaged file is refused here, with our message and
// without that noise. A damaged zlib stream inside valid chunks still
// reaches libpng.
#include <cstdint>
#include <string>
#include <vector>

namespace tsr::sg {

// Empty when the chunk structure is sound, else why it is not.
std::string pngStructureProblem(const std::vector<std::uint8_t>& bytes);

}  // namespace tsr::sg
