#pragma once
// Pixel filtering (Schwenk ch. 3) on a viewport's frame. Its inputs travel
// as named outputs, so the same resolve runs on a whole local frame and on
// a frame a cluster client assembled from tiles: both give one image.
#include <optional>
#include <string>
#include <vector>

#include "filter_settings.hpp"
#include "tsr/embree/framebuffer.hpp"
#include "tsr/embree/pixel_filter.hpp"
#include "tsr/embree/radiance_filter.hpp"
#include "tsr/med/frame_buffer.hpp"

namespace tsr::med::embree_mediator {

inline constexpr const char* kLowVarianceOutput = "filter.lowVariance";      // rgb: Llv
inline constexpr const char* kHighVarianceOutput = "filter.highVariance";    // rgb: Lu
inline constexpr const char* kHighVarianceVarOutput = "filter.variance";     // rgb: Var[Lu] of the mean
inline constexpr const char* kRangeOutput = "filter.range";                  // rgb: flash colour, a: samples n
inline constexpr const char* kRangeGeometryOutput = "filter.rangeGeometry";  // r: std. dev. of the flash samples,
                                                                             // g: their mean depth (inf: none hit)
inline constexpr const char* kBlendOutput = "blend";                         // r: blend factor s

std::vector<std::string> pixelFilterInputs();

// Flash samples a frame of n path samples is filtered with: 4 per filter
// pass of the 4, 8, 16, ... schedule (3.3.3), so the count depends on n
// alone and a tile rendered on a node matches the whole-frame render.
std::uint32_t flashSamplesFor(std::uint32_t samples);

// Writes the filter's inputs from the accumulated samples into `out`. With
// `hybrid`, out's colour is radiance filtering's image and what is left to
// pixel filtering is per pixel: see hybrid filtering in backends/embree/README.md.
void writePixelFilterInputs(const embree::FrameBuffer& fb, PathClass pathClass, FrameBuffer& out,
                            const embree::RadianceAccumulator* hybrid = nullptr);

// Filters and blends frames from their filter outputs; keeps the last
// filtered buffer, so that frames between two filter passes only blend. The
// kept buffer belongs to one accumulation (embree::FrameBuffer::epoch): when
// the path tracer restarts it, the buffer is no longer used.
class PixelFilterResolver {
 public:
  // Replaces frame's colour (rgb) with the blended image; filters anew when
  // `refilter`, when nothing of accumulation `epoch` was filtered yet, or
  // when the settings or the frame's size changed. Fills the "blend" output
  // when `blendOutput`.
  void resolve(FrameBuffer& frame, const FilterSettings& settings, bool refilter, bool blendOutput,
               std::uint64_t epoch);
  // The sample count the kept filtered buffer of accumulation `epoch` was made from.
  std::optional<std::uint32_t> filteredAt(std::uint64_t epoch) const;

 private:
  std::optional<embree::FilteredBuffer> filtered_;
  embree::PixelFilterSettings filteredWith_;
  std::uint64_t filteredEpoch_ = 0;
};

}  // namespace tsr::med::embree_mediator
