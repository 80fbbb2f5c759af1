#pragma once
// Radiance filtering (Schwenk 2013, chapter 4): each radiance pass traces one
// path per pixel, keeps its direct light as usual and stores the indirect
// light incident at the path's first non-specular vertex as a radiance
// sample; a filtering step then re-uses the samples of neighbouring pixels,
// reflected by each pixel's own BSDF, with kernels that shrink as the image
// converges. Renderer::renderRadiancePass runs both steps.
#include "tsr/embree/material.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace tsr::embree {

class FrameBuffer;

// Parameters of the filtering step. They may change while an image
// converges; changing them does not restart accumulation.
struct RadianceFilterSettings {
  float threshold = 0.01f;    // T_u: target perceived variance (variance / background radiance^2) of the result
  float warmupRadius = 8.0f;  // r_w1: kernel radius in pixels of frame 1; frame k <= warmupFrames uses r_w1/sqrt(k)
  std::uint32_t warmupFrames = 4;  // frames with the warm-up radius before the variance estimate is trusted (>= 1)
  float maxRadius = 12.0f;         // hard cap on the kernel radius in pixels; a crop needs a halo this wide, see README
  bool ambientOcclusion = true;    // scale radii by screen-space ambient occlusion of the previous frame (4.3.1)
  bool bilateral = false;          // range term on the filtered irradiance (4.6.2), from frame kBilateralStart on
  float blend = 0.0f;              // share of T_k left to unfiltered samples (4.6.3 blending operator); 0 = off, < 1
  bool hybrid = true;              // leave pixels seen through a reflecting-and-refracting surface unfiltered (4.6.1)

  // Throws Error on values outside the ranges above or non-finite ones.
  void validate() const;
};

// Bits of RadianceAccumulator::mask (4.6.1), ORed over the frames: what the
// path met before its radiance sample, i.e. before its first non-specular
// vertex.
enum RadianceMask : std::uint8_t {
  kMaskSpecular = 1,        // a perfect specular surface (Mirror or Glass)
  kMaskReflectRefract = 2,  // a surface that reflects and refracts (Glass): for pixel filtering
};

// One path's radiance sample, at its first non-specular vertex (4.3.1 steps 1-2).
struct RadianceSample {
  bool valid = false;                         // the path reached a non-specular surface
  glm::vec3 position{0.0f};                   // x_j, world space
  glm::vec3 normal{0.0f};                     // shading normal on the side of wo
  glm::vec3 wo{0.0f};                         // towards the previous vertex (the eye or the last specular surface)
  glm::vec3 wi{0.0f};                         // sampled incident direction (zero if the path ended here)
  glm::vec3 radiance{0.0f};                   // Ľ_i: indirect radiance arriving from wi, not divided by pdf
  float pdf = 0.0f;                           // solid-angle density of wi at x_j (0 if the path ended here)
  glm::vec3 throughput{1.0f};                 // product of the specular chain's weights from the eye to x_j
  float distance = 0.0f;                      // path length from the eye to x_j through the specular chain
  float pixelAngle = 0.0f;                    // angle one pixel subtends at the eye along this camera ray (radians)
  MaterialType type = MaterialType::Diffuse;  // BSDF at x_j, to re-evaluate it for other samples
  glm::vec3 colour{0.0f};                     // base colour (textured) at x_j
  float alpha = 1.0f;                         // GGX alpha at x_j
  float eta = 1.0f;                           // index ratio across the surface seen from wo
  float metallic = 0.0f;                      // MetallicRoughness parameters at x_j
  float specular = 1.0f;
  float transmission = 0.0f;
  glm::vec3 unfiltered{0.0f};  // this path's indirect pixel estimate: throughput * f cos / pdf * Ľ_i
  std::uint8_t mask = 0;       // RadianceMask bits met before x_j
};

// Region-sized state of radiance filtering: per pixel the running mean of
// the per-frame filtered indirect estimates, the frame count, the filtered
// perceived variance, ambient occlusion and irradiance carried to the next
// frame, the last radius and the hybrid mask. Belongs to one FrameBuffer:
// it restarts whenever that buffer restarts (or it is used with another).
class RadianceAccumulator {
 public:
  RadianceAccumulator(std::uint32_t width, std::uint32_t height);

  std::uint32_t width() const { return width_; }
  std::uint32_t height() const { return height_; }
  void reset();

  // Frames accumulated into pixel (x, y) (region coordinates).
  std::uint32_t frames(std::uint32_t x, std::uint32_t y) const { return pixels_[at(x, y)].frames; }
  // Accumulated filtered indirect radiance, caustics excluded (unfiltered
  // for masked pixels with hybrid on, and for pixels whose path hit no
  // non-specular surface). Caustic paths (LS+D..E) are never filtered
  // here: a neighbour's rare caustic sample, re-used by every pixel in
  // its kernel, would print a disc-shaped splotch; they stay in the frame
  // buffer's Caustic channel, for pixel filtering to handle (hybrid).
  glm::vec3 indirect(std::uint32_t x, std::uint32_t y) const { return pixels_[at(x, y)].indirect; }
  // The pixel's value: direct and caustics (from the frame buffer it
  // belongs to, unfiltered) + indirect, the accumulated filtered estimate
  // blended with the frame buffer's unfiltered one by their perceived
  // variance against the threshold (3.12 with f = 0): converges to the
  // unfiltered image.
  // Read through radiance(fb, x, y), or radianceImage(fb).
  glm::vec3 radiance(const FrameBuffer& fb, std::uint32_t x, std::uint32_t y) const;
  std::vector<glm::vec3> radianceImage(const FrameBuffer& fb) const;
  // Kernel radius in pixels used in the last frame; 0 = unfiltered sample.
  float radius(std::uint32_t x, std::uint32_t y) const { return pixels_[at(x, y)].radius; }
  // Filtered perceived variance of one sample (4.3.4), used for the next radius.
  float variance(std::uint32_t x, std::uint32_t y) const { return pixels_[at(x, y)].variance; }
  // Screen-space ambient occlusion factor in [0, 1] (1 = open).
  float occlusion(std::uint32_t x, std::uint32_t y) const { return pixels_[at(x, y)].occlusion; }
  // RadianceMask bits, ORed over the frames.
  std::uint8_t mask(std::uint32_t x, std::uint32_t y) const { return pixels_[at(x, y)].mask; }
  // The radiance sample of the last frame.
  const RadianceSample& sample(std::uint32_t x, std::uint32_t y) const { return samples_[at(x, y)]; }

 private:
  friend class Renderer;
  friend struct RadianceFilterStep;

  struct Pixel {
    std::uint32_t frames = 0;
    glm::vec3 indirect{0.0f};
    float irradiance = 0.0f;  // running mean of the filtered irradiance's luminance (bilateral range term)
    float variance = 0.0f;
    float occlusion = 1.0f;
    float radius = 0.0f;
    std::uint8_t mask = 0;
  };

  std::size_t at(std::uint32_t x, std::uint32_t y) const { return std::size_t(y) * width_ + x; }

  std::uint32_t width_;
  std::uint32_t height_;
  std::uint64_t epoch_ = 0;  // FrameBuffer::epoch() of the buffer the state belongs to
  float threshold_ = 0.0f;   // T_u of the last filter step, for the blend in radiance()
  std::vector<Pixel> pixels_;
  std::vector<RadianceSample> samples_;  // this frame's, written by the tracing step
};

// Frame from which the bilateral range term is applied: the irradiance it
// compares needs this many samples to show edges (4.6.2 reports 16-32).
inline constexpr std::uint32_t kBilateralStart = 16;

}  // namespace tsr::embree
