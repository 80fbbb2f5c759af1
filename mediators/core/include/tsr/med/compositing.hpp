#pragma once
// Layered viewports become one image: per pixel the nearer layer goes over
// the farther one by its alpha; on equal depth the later layer is on top.
#include "tsr/med/frame_buffer.hpp"

namespace tsr::med {

// Composites `layer` into `base` (same size). Colours are straight (not
// premultiplied) RGBA with alpha as coverage.
void compositeByDepth(FrameBuffer& base, const FrameBuffer& layer);

enum class AnaglyphMethod {
  RedCyan,  // red from the left eye, green and blue from the right
  // Dubois's least-squares red/cyan projection: the colours seen through the
  // filters are as near as the filters allow (in CIE XYZ) to the colours
  // each eye should see, which keeps more colour and less retinal rivalry.
  Dubois,
};

// One image for red/cyan glasses, applied to linear RGB (as frame buffers
// hold it); Dubois's result is clamped to [0, 1]. Depth is the nearer eye's.
FrameBuffer anaglyph(const FrameBuffer& left, const FrameBuffer& right,
                     AnaglyphMethod method = AnaglyphMethod::RedCyan);
// Left and right next to each other.
FrameBuffer sideBySide(const FrameBuffer& left, const FrameBuffer& right);

}  // namespace tsr::med
