#pragma once
// Layered viewports become one image: per pixel the nearer layer goes over
// the farther one by its alpha; on equal depth the later layer is on top.
#include "tsr/med/frame_buffer.hpp"

namespace tsr::med {

// Composites `layer` into `base` (same size). Colours are straight (not
// premultiplied) RGBA with alpha as coverage.
void compositeByDepth(FrameBuffer& base, const FrameBuffer& layer);

// Red/cyan anaglyph: red from the left eye, green and blue from the right.
FrameBuffer anaglyph(const FrameBuffer& left, const FrameBuffer& right);
// Left and right next to each other.
FrameBuffer sideBySide(const FrameBuffer& left, const FrameBuffer& right);

}  // namespace tsr::med
