#pragma once
// The methods of the whole-image denoiser (tsr/embree/denoiser.hpp), each
// on input denoise() has checked.
#include "tsr/embree/denoiser.hpp"

namespace tsr::embree::detail {

// The least albedo a channel is divided by (emitters, black surfaces and
// the background have none). Every pixel is demodulated, or pixels in two
// different units would be averaged where a texture goes dark.
inline constexpr float kMinDenoiseAlbedo = 0.02f;

std::vector<glm::vec3> regressionDenoise(const DenoiseInput& input, const DenoiseSettings& settings);
std::vector<glm::vec3> atrousDenoise(const DenoiseInput& input, const DenoiseSettings& settings);

}  // namespace tsr::embree::detail
