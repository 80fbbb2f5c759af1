#pragma once
// Image files and encoded images (PNG, JPEG, EXR, ...) through OpenImageIO.
//
// OpenImageIO as Debian builds it brings about 250 shared libraries with it
// (FFmpeg, OpenCV, GDCM, ...): linked into a program, the dynamic loader
// spends a third of a second and 100 MB on them at every start, whether or
// not the program ever touches an image. So OpenImageIO lives in a module
// of its own (libtsr_imageio_oiio.so), loaded the first time one of these
// functions runs; a render node, a test or a service that reads and writes
// no image never loads it. Depends on nothing of ours.
#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace tsr::imageio {

// Any failure: the file or bytes, and what went wrong, in words a person
// can act on (also: the module cannot be found or loaded).
class CodecError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class Sample : std::uint8_t { UInt8, Float };

// The layout of interleaved pixels, row 0 at the top.
struct Layout {
  std::uint32_t width = 0, height = 0, channels = 0;
  Sample sample = Sample::UInt8;
  std::vector<std::string> channelNames;  // empty: the format's defaults (R, G, B, A)
  int alphaChannel = -1;                  // -1: none named
  int depthChannel = -1;                  // -1: none named
  int pngCompression = -1;                // zlib level 0-9 for PNG; -1: the library's default
  bool straightAlpha = false;             // colours not premultiplied by alpha (as glTF stores them)
};

struct Image {
  std::uint32_t width = 0, height = 0, channels = 0;
  bool floatingPoint = false;  // what the file stores (false: 8/16-bit integers, sRGB as a rule)
  std::vector<std::string> channelNames;
  std::vector<float> floats;        // when read as Sample::Float
  std::vector<std::uint8_t> bytes;  // when read as Sample::UInt8
};

// Writes `pixels` (layout.sample values, interleaved) to `path` in the
// format that `formatName`'s extension names (the path itself may be a
// temporary name without one).
void writeFile(const std::string& path, const std::string& formatName, const Layout& layout,
               std::span<const std::byte> pixels);

// The same, into memory (a streamed frame).
std::vector<std::uint8_t> encode(const std::string& formatName, const Layout& layout,
                                 std::span<const std::byte> pixels);

// Reads the whole first subimage, converted to `as`.
Image readFile(const std::string& path, Sample as);

// Decodes bytes held in memory in the format `formatName`'s extension
// names, 8 bits per channel, alpha as stored (not premultiplied). Refuses
// images of more than `maxPixels` pixels or more than four channels before
// decoding them.
Image decode(std::span<const std::uint8_t> encoded, const std::string& formatName, std::uint64_t maxPixels);

// Where the module was loaded from (loads it): for diagnostics.
std::string modulePath();

}  // namespace tsr::imageio
