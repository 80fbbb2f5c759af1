#pragma once

// Image-space part of pixel filtering (Schwenk 2013, chapter 3): an
// edge-preserving filter of the high-variance buffer guided by a noise-free
// "virtual flash" range buffer, and the blend of filtered and unfiltered
// radiance that keeps the perceived variance below a threshold t. Pure
// functions: images in, images out. See ../../../README.md, "Pixel filter".

#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace tsr::embree {

// Which edge-preserving filter computes Lf.
enum class FilterKernel {
  Bilateral,  // brute-force cross bilateral (3.6), exact r = sum (a_i/A)^2
  Separable,  // iterated 1-D passes with shrinking sigma (3.14); r estimated (README: "r through several passes")
  Atrous,     // a-trous wavelet (Dammertz et al.) with the range buffer as edge stop (3.5.1.2)
};

struct PixelFilterSettings {
  FilterKernel kernel = FilterKernel::Bilateral;  // filter used by filterHighVariance
  float threshold =
      0.01f;            // t of 3.11 on perceived variance Var/Lb^2; 0.01 = 10% relative std. dev., the default of 3.5.2
  float sigmaS = 8.0f;  // spatial std. dev. in pixels (combined over passes); kernel truncated at 3 sigma
  float sigmaC = 0.02f;  // range std. dev. of the Euclidean distance of linear-RGB range colours
  float sigmaD = 1.0f;   // range std. dev. of depth, world units; +inf ignores depth (background is still kept apart)
  bool adaptiveWidth = false;      // per-pixel sigma from u and the target f (3.15-3.17, c = 4)
  float adaptiveTarget = 0.5f;     // target f of 3.15 as a fraction of threshold (f < t so the blend can reach t)
  bool spikeRemoval = false;       // clamp Lu to [Lf/c, c Lf] per channel before blending (3.18, c = 2 up to 8 spp,
                                   // growing as sqrt(n/8) after, so the clamp's bias fades as the image converges)
  bool antialiasRecovery = false;  // edge model with three range windows (3.19-3.20); Separable kernel only
  unsigned iterations = 3;         // N of 3.14 (Separable) / number of a-trous levels (Atrous); >= 1
  float minBackground = 1e-3f;     // floor on the luminance Lb (3.10) so u = Var/Lb^2 stays finite on black
  int threads = 0;                 // TBB worker threads; 0 = all
};

// Region-sized input images, row-major, row 0 at the top; every span holds
// width * height entries.
struct PixelFilterInput {
  std::uint32_t width = 0;                     // image width in pixels
  std::uint32_t height = 0;                    // image height in pixels
  std::span<const glm::vec3> highVariance;     // Lu: mean radiance of the high-variance paths
  std::span<const glm::vec3> highVarianceVar;  // variance of that mean (per-sample variance / n), per channel
  std::span<const glm::vec3> lowVariance;      // Llv: mean radiance of the low-variance paths
  std::span<const glm::vec3> rangeColour;      // c_i: "virtual flash" colour, linear RGB
  std::span<const float> rangeDepth;           // d_i: camera-space depth; +inf (or any non-finite) = background
  std::uint32_t samples = 0;                   // n: samples per pixel so far (guide line of 3.17)
  std::span<const float> rangeSpread;          // e_i: std. dev. of the pixel's flash samples; empty = all 0
};

// Result of the expensive step, recomputed on the isFilterFrame schedule.
struct FilteredBuffer {
  std::uint32_t width = 0;          // same size as the input
  std::uint32_t height = 0;         // same size as the input
  std::uint32_t samples = 0;        // n of the input it was filtered from (blend rescales Var[Lu] by this/n)
  std::vector<glm::vec3> radiance;  // Lf: filtered Lu
  std::vector<float> variance;      // filtered scalar Var[Lu]: luminance-weighted sum of channel variances
  std::vector<float> reduction;     // r ~ sum (a_i/A)^2 of the (composite) kernel, in (0, 1]
  std::vector<float> sigma;         // spatial sigma used per pixel (sigmaS unless adaptiveWidth)
};

// Filters Lu (and its variance) with the cross bilateral weights of the range
// buffer. Throws tsr::embree::Error on inconsistent sizes or settings.
FilteredBuffer filterHighVariance(const PixelFilterInput& input, const PixelFilterSettings& settings);

struct BlendResult {
  std::vector<glm::vec3> radiance;  // final pixel: Llv + s Lu' + (1 - s) Lf (3.1)
  std::vector<float> blendFactor;   // s per pixel, 1 = unfiltered only
};

// Luminance (Rec. 709 / linear sRGB weights); also the weights of the scalar variance.
float luminance(const glm::vec3& c);

// s of 3.12 with the cases of 3.13 for perceived variances u (unfiltered),
// f (filtered) and threshold t. Non-finite or negative u gives 0.
float blendFactor(float u, float f, float t);

// Blends the current Lu with a (possibly older) FilteredBuffer of the same
// size: Lb = lum(Lf + Llv) (3.10), u = Var/Lb^2, f = r u (3.5), s (3.13),
// optional spike removal (3.18). Throws tsr::embree::Error on size mismatch.
BlendResult blend(const PixelFilterInput& input, const FilteredBuffer& filtered, const PixelFilterSettings& settings);

// True on the frames (1-based count of rendered frames) on which the filter
// is re-run: 4, 8, 16, 32, ...
bool isFilterFrame(std::uint32_t frame);

}  // namespace tsr::embree
