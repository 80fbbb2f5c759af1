#pragma once
// Frame buffers to files through OpenImageIO, the format chosen by the
// extension: float formats (EXR, PFM, HDR) keep radiance as it is; 8-bit
// ones (PNG, JPEG, ...) are clamped and sRGB-encoded, after the display
// transform (exposure, tone curve) for radiance outputs.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "tsr/med/display_transform.hpp"
#include "tsr/med/frame_buffer.hpp"

namespace tsr::med {

class ImageFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Writes colour, or the named output (e.g. "albedo", "depth") when given.
// `display` applies to 8-bit formats and to radiance (colour, direct,
// indirect), never to albedo, normals, depth or statistics.
void writeImage(const std::string& path, const FrameBuffer& fb, const std::string& output = "colour",
                const DisplayTransform& display = {});
// Writes one OpenEXR file with colour (R, G, B, A), depth (Z) and every
// named output as a layer ("albedo.R", "albedo.G", "albedo.B", ...): what a
// compositor opens as AOVs. Throws ImageFileError unless `path` ends in .exr.
void writeLayeredExr(const std::string& path, const FrameBuffer& fb);
// Colour after `display`, as an 8-bit sRGB PNG in memory (a streamed frame).
std::vector<std::uint8_t> encodePng(const FrameBuffer& fb, const DisplayTransform& display = {});
// Reads an image back as RGBA float (linear for float files, sRGB decoded otherwise).
FrameBuffer readImage(const std::string& path);

}  // namespace tsr::med
