#pragma once
// Noise-filter settings of an Embree viewport, read from its parameters.
// All of them may change while an image converges: none restarts
// accumulation, they only change how the accumulated samples are shown.
//
//   filter      none | pixel | atrous | radiance | hybrid | denoise  (none)
//   threshold   t: perceived variance the blend keeps under  (0.01)
//   sigmaS      spatial std. dev., pixels                     (8)
//   sigmaC      range colour std. dev.                        (0.02)
//   sigmaD      range depth std. dev., as a fraction of the
//               frame's depth extent (nearest to farthest hit) (0.1)
//   pathClass   indirect | caustic | all: the paths filtered  (indirect)
//   filterKernel  bilateral | separable, for filter=pixel      (bilateral)
//   adaptiveWidth, spikeRemoval, antialiasRecovery  (false, true, false)
// Radiance filtering (filter=radiance|hybrid) reads threshold too (T_u of
// 4.3.3), and:
//   warmupRadius (8 px), warmupFrames (4), maxRadius (12 px: cluster tiles
//   are traced with a halo this wide), ambientOcclusion (true),
//   bilateral (false), radianceBlend (0)
// The whole-image denoiser (filter=denoise, tsr/embree/denoiser.hpp):
//   denoiseMethod regression | atrous  (regression)
//   regression: denoiseRadius (7), denoisePatch (3)
//   atrous: denoiseLevels (5), denoiseSigmaL (2), denoiseSigmaN (64), denoiseSigmaZ (1)
#include <string>

#include "tsr/embree/denoiser.hpp"
#include "tsr/embree/pixel_filter.hpp"
#include "tsr/embree/radiance_filter.hpp"
#include "tsr/med/parameters.hpp"

namespace tsr::med::embree_mediator {

enum class FilterMode { None, Pixel, Atrous, Radiance, Hybrid, Denoise };
enum class PathClass { Indirect, Caustic, All };

struct FilterSettings {
  FilterMode mode = FilterMode::None;
  PathClass pathClass = PathClass::Indirect;
  float sigmaDRelative = 0.1f;
  embree::PixelFilterSettings pixel;  // sigmaD is set per frame from sigmaDRelative
  embree::RadianceFilterSettings radiance;
  embree::DenoiseSettings denoise;

  // Throws ParameterError naming the parameter and what it accepts.
  static FilterSettings from(const Parameters& parameters);
  bool usesPixelFilter() const {
    return mode == FilterMode::Pixel || mode == FilterMode::Atrous || mode == FilterMode::Hybrid;
  }
  bool usesRadianceFilter() const { return mode == FilterMode::Radiance || mode == FilterMode::Hybrid; }
  bool usesDenoiser() const { return mode == FilterMode::Denoise; }
};

}  // namespace tsr::med::embree_mediator
