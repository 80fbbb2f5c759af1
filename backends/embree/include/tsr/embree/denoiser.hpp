#pragma once
// A denoiser for the whole image (direct, indirect, caustic and specular
// light together), guided by what the path tracer knows per pixel: the
// albedo and normal of the first surface, depth, and the variance of the
// pixel's mean. Textures are kept by demodulating the colour by the albedo
// and modulating it back afterwards; edges by the normal and depth; what
// the image itself shows (highlights, shadow edges) by comparing
// neighbours' luminance in units of their standard error, so the filter
// lets go of a pixel as its samples converge. The kernel is the
// edge-avoiding a-trous wavelet with those three stopping functions and
// the variance carried through its levels (Dammertz et al. 2010; Schied
// et al. 2017, SVGF, its spatial part). Pure function: images in, image out.
#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace tsr::embree {

struct DenoiseSettings {
  unsigned levels = 5;          // a-trous levels: the footprint is 4 * (2^levels - 1) + 1 pixels wide
  float sigmaLuminance = 2.0f;  // luminance difference allowed, in standard errors of the pixels' means
  float sigmaNormal = 64.0f;    // exponent on the cosine between normals
  float sigmaDepth = 1.0f;      // depth difference allowed, in units of the local depth gradient per pixel
  int threads = 0;              // TBB worker threads; 0 = all
};

// Region-sized input images, row-major, row 0 at the top; every span holds
// width * height entries.
struct DenoiseInput {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::span<const glm::vec3> colour;    // the pixel's mean radiance
  std::span<const glm::vec3> variance;  // variance of that mean (per-sample variance / n), per channel
  std::span<const glm::vec3> albedo;    // mean albedo of the first surface
  std::span<const glm::vec3> normal;    // mean normal of the first surface (need not be unit)
  std::span<const float> depth;         // camera-space depth; non-finite: nothing hit
};

// The denoised image. Throws tsr::embree::Error on inconsistent sizes or
// settings.
std::vector<glm::vec3> denoise(const DenoiseInput& input, const DenoiseSettings& settings);

}  // namespace tsr::embree
