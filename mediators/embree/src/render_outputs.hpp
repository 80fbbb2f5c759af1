#pragma once
// What every Embree viewport reads from its parameters and view, and how it
// hands an accumulation buffer back as a med::FrameBuffer.
#include <string>
#include <vector>

#include "tsr/embree/framebuffer.hpp"
#include "tsr/embree/renderer.hpp"
#include "tsr/med/viewport.hpp"

namespace tsr::med::embree_mediator {

// The named outputs fill() offers besides colour and depth.
std::vector<std::string> accumulatedOutputNames();

// Colour and depth of `fb`, and the named outputs the caller reads
// (control.wants): all five cost about a tenth of a 16-spp pass at 512².
FrameBuffer accumulatedFrame(const embree::FrameBuffer& fb, const RenderControl& control);
// The same outputs of a Whitted image (one sample: no indirect light, no
// variance), written into `out` in place: a frame a viewer asks for again
// and again reuses its memory instead of faulting in 30 MB of fresh pages.
void writeWhittedFrame(const embree::WhittedImage& image, const RenderControl& control, FrameBuffer& out);

}  // namespace tsr::med::embree_mediator
