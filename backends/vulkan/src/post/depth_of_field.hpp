#pragma once
// Depth of field for the rasterizer: the camera's thin lens (apertureRadius,
// focusDistance), as the path tracer traces it, made from the sharp image
// and its depth after the frame. A point at depth z is seen by the lens as
// a disk on the image of radius
//   coc(z) = apertureRadius * |z - focusDistance| / z
// at the focus plane, in pixels there: a uniform disk, as the path tracer's
// lens samples are uniform over the aperture. Each pixel gathers the
// neighbours whose disks cover it ("scatter as gather"), each weighted by
// the inverse of its disk's area, so a blurred region keeps its energy; a
// neighbour behind the pixel spreads no farther than the pixel's own disk,
// so a blurred background does not bleed over a sharper foreground.
#include "tsr/vk/vocabulary.hpp"

#include <glm/vec4.hpp>

#include <cstdint>
#include <span>

namespace tsr::vk {

// Disks are cut to this radius in pixels: it bounds the work a pixel does.
inline constexpr float kMaxBlurPixels = 32.0f;
// What a crop of the image is drawn with around it (Renderer::render) so its
// pixels blur exactly as the whole image's: the farthest a pixel gathers
// from, and the tiles (aligned to the whole image) that decide how far.
inline constexpr std::uint32_t kBlurTile = 8;
inline constexpr std::uint32_t kBlurMargin = std::uint32_t(kMaxBlurPixels) + 2 * kBlurTile;

// Pixels a unit of coc() covers in the image of `region` (its full width).
float blurPixelsPerUnit(const Camera& camera, const Region& region);

// The blur radius in pixels of a point at camera depth z (infinity: what
// lies beyond everything), at most kMaxBlurPixels.
float blurRadius(const Camera& camera, float pixelsPerUnit, float z);

// Blurs `colour` (the pixels of `drawn`, row 0 at the top) by the lens
// from `depth` (camera-space depth, +infinity where nothing was drawn).
// Colour and alpha blur alike; depth is left as it is. A pixel's result
// depends on the pixels within kBlurMargin of it only.
void applyDepthOfField(const Camera& camera, const Region& drawn, std::span<glm::vec4> colour,
                       std::span<const float> depth);

}  // namespace tsr::vk
