#pragma once
// A denoiser for the whole image (direct, indirect, caustic and specular
// light together), guided by what the path tracer knows per pixel: the
// albedo and normal of the first surface, depth, the variance of the
// pixel's mean, the means of two halves of its samples and the emission
// seen from the camera. Textures are kept by demodulating the colour by the
// albedo and modulating it back afterwards; emission is taken out before
// and put back after. Two methods:
//  - regression (the default): weighted first-order regression on the
//    features over a window, weighted by non-local means on the colour of
//    the other half of the samples, the window's fits averaged
//    (collaborative); per pixel, the unfiltered mean and two strengths are
//    candidates and the one whose error, estimated from the halves, is
//    lowest is taken (Bitterli et al. 2016, NFOR, without its feature
//    prefiltering and second pass). Variances come from the halves'
//    difference, not from the samples' spread: stratified samples make a
//    pixel's mean far better than spread / N where it straddles an edge;
//  - atrous: the edge-avoiding a-trous wavelet stopped by normal, depth
//    and luminance in standard errors, the variance carried through its
//    levels (Dammertz et al. 2010; Schied et al. 2017, SVGF, its spatial
//    part): cheaper, weaker at few samples.
// Pure function: images in, image out.
#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace tsr::embree {

enum class DenoiseMethod { Regression, Atrous };

struct DenoiseSettings {
  DenoiseMethod method = DenoiseMethod::Regression;
  // regression: the window is (2 radius + 1)^2 pixels, the non-local means
  // patches (2 patchRadius + 1)^2.
  unsigned radius = 7;
  unsigned patchRadius = 3;
  // atrous:
  unsigned levels = 5;          // a-trous levels: the footprint is 4 * (2^levels - 1) + 1 pixels wide
  float sigmaLuminance = 2.0f;  // luminance difference allowed, in standard errors of the pixels' means
  float sigmaNormal = 64.0f;    // exponent on the cosine between normals
  float sigmaDepth = 1.0f;      // depth difference allowed, in units of the local depth gradient per pixel
  int threads = 0;              // TBB worker threads; 0 = all

  bool operator==(const DenoiseSettings&) const = default;
};

// Region-sized input images, row-major, row 0 at the top; every span holds
// width * height entries.
struct DenoiseInput {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::span<const glm::vec3> colour;    // the pixel's mean radiance
  std::span<const glm::vec3> variance;  // variance of that mean (per-sample variance / n), per channel;
                                        // read by atrous only (regression estimates it from the halves)
  std::span<const glm::vec3> albedo;    // mean albedo of the first surface
  std::span<const glm::vec3> normal;    // mean normal of the first surface (need not be unit)
  std::span<const float> depth;         // camera-space depth; non-finite: nothing hit
  // regression only: the mean of colour - emitted over the pixel's first
  // half of its samples (FrameBuffer::firstHalf) and that half's share of
  // the samples (0 to 1; 0.5 at a power-of-two count, 0 when the pixel has
  // one sample).
  std::span<const glm::vec3> firstHalf;
  std::span<const float> firstHalfShare;
  // Optional (empty: none): emission seen from the camera
  // (FrameBuffer::emitted), part of colour. It is taken out before
  // filtering and put back after: a lamp or the sky is only as noisy as
  // its coverage of the pixel, and averaged with what surrounds it, it
  // would glow over its neighbours.
  std::span<const glm::vec3> emitted;
};

// The denoised image. Throws tsr::embree::Error on inconsistent sizes or
// settings.
std::vector<glm::vec3> denoise(const DenoiseInput& input, const DenoiseSettings& settings);

}  // namespace tsr::embree
