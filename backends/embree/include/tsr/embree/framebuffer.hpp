#pragma once

#include "tsr/embree/render_settings.hpp"
#include "tsr/embree/vocabulary.hpp"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <vector>

namespace tsr::embree {

// Radiance channels that keep a running mean and variance. Colour is Direct +
// Indirect. Direct is emission seen directly or through perfect specular
// surfaces, and light that reaches the first non-specular surface straight
// from an emitter; Indirect is the rest. Caustic is the part of Indirect
// that passed a perfect specular surface after a non-specular one (LS+D..E
// read from the light): the paths that make fireflies.
enum class Channel { Colour = 0, Direct = 1, Indirect = 2, Caustic = 3 };
inline constexpr int kChannels = 4;

// PixelSample::object of a camera ray that hit nothing.
inline constexpr std::uint32_t kNoObject = std::numeric_limits<std::uint32_t>::max();

// What one camera sample produced; used by the renderer to accumulate.
struct PixelSample {
  glm::vec3 direct{0.0f};
  glm::vec3 indirect{0.0f};
  glm::vec3 caustic{0.0f};  // part of indirect
  // Emission seen from the camera, straight or through perfect mirrors and
  // clear glass (part of direct): lamps and sky as they appear, whose only
  // noise is which samples cover them. The denoiser leaves it as it is.
  glm::vec3 emitted{0.0f};
  bool hit = false;
  float depth = 0.0f;                // camera-space depth of the first hit, if hit
  std::uint32_t object = kNoObject;  // the instance of the first hit (its index in the scene), if hit
  glm::vec3 albedo{0.0f};
  glm::vec3 normal{0.0f};
};

// Accumulates samples of one region, per pixel. Each pixel keeps its own
// sample count, so a pass interrupted midway leaves every pixel consistent.
//
// Outputs per pixel (x, y relative to the region):
//  - colour: mean radiance, alpha = fraction of samples whose camera ray hit geometry
//  - mean/variance per Channel: Welford running mean and the unbiased sample
//    variance of one sample (divide by sampleCount for the mean's variance)
//  - depth: camera-space depth (distance along the view axis, -Z in camera
//    space) of the nearest first hit over the samples; +infinity if none hit
//  - albedo, normal: mean base colour and world shading normal (facing the
//    camera) at the first hit; zero on misses
//  - emitted: mean of PixelSample::emitted
//  - first half: the mean of colour minus emitted over the pixel's first
//    P/2 samples, P the largest power of two not above its count. At a power-of-two count the
//    two halves are the first and the second half of the samples, each an
//    aligned block of the sampler's sequence and so stratified on its own
//    (splitting by parity would not be: the even points of a Sobol
//    sequence share half of each pixel). The denoiser compares the halves.
//  - range colour: mean "virtual flash" colour (Renderer::renderFlashPass),
//    the edge-stopping image of pixel filtering; zero until a flash pass ran;
//    camera rays that hit nothing count as kFlashMiss
//  - range spread: the standard deviation of the pixel's flash samples
//    (the norm of the colour deviation), high where a pixel mixes surfaces
//  - range depth: the mean camera-space depth of the flash samples that hit
//    (+infinity if none did), the depth that goes with the range colour:
//    the depth output is the nearest over the path samples, which jitter
//    apart from the flash samples, so a silhouette pixel could pair the
//    wall's colour with the box's depth and match nothing
// The flash colour of a camera ray that hits nothing: outside the colours
// any surface reflects (they are never negative), so a pixel that mixes a
// surface with the background matches neither, nor gathers either.
inline constexpr glm::vec3 kFlashMiss{-1.0f};

// What an image was rendered for; any difference restarts it.
struct FrameKey {
  std::uint64_t sceneUid = 0;
  std::uint64_t sceneVersion = 0;
  Camera camera;
  Region region;
  RenderSettings settings;      // imageSettings: what changes the samples
  std::uint64_t estimator = 0;  // plain paths, radiance records, one irradiance field's uid, or Whitted
  // Scene::appearanceVersion: unchanged when only instances moved, so the
  // samples may be carried to the new placement (FrameBuffer::reproject).
  std::uint64_t sceneAppearance = 0;
  bool operator==(const FrameKey&) const = default;
};

// What a frame buffer's history is carried across (FrameBuffer::reproject):
// the camera and region its samples were taken for and the ones wanted now,
// each instance's placement (world from object, by instance index; an
// instance missing from either list carries nothing) then and now, and the
// most samples a pixel may carry, so that light which changed while moving
// fades out of the history within that many samples.
struct Reprojection {
  Camera fromCamera, toCamera;
  Region fromRegion, toRegion;
  std::span<const glm::mat4> placedThen, placedNow;
  std::uint32_t historyLimit = 16;
};

class FrameBuffer {
 public:
  FrameBuffer(std::uint32_t width, std::uint32_t height);

  std::uint32_t width() const { return width_; }
  std::uint32_t height() const { return height_; }

  void reset();
  // Changes whenever the buffer restarts, unique across buffers: state kept
  // alongside (RadianceAccumulator) compares it to know it is stale.
  std::uint64_t epoch() const { return epoch_; }
  void accumulate(std::uint32_t x, std::uint32_t y, const PixelSample& sample);

  // Restarts as reset() does, but each pixel first takes over what the old
  // samples knew of the surface it shows now (temporal reprojection, after
  // SVGF and the render cache): the old depths are splatted into the new view
  // (instances moved as placed) to predict what each pixel sees, and the
  // pixel gathers, bilinearly, the old pixels that saw the same instance at
  // that depth; their counts, capped at r.historyLimit, become the pixel's
  // inherited samples. Its first new sample
  // checks the prediction: if it hits another instance, another depth, a
  // surface facing elsewhere, or nothing where something was, the pixel
  // drops what it inherited. The old samples must be of r.from*; the key
  // they were rendered for stays (the renderer sets the new one).
  void reproject(const Reprojection& r);

  std::uint32_t sampleCount(std::uint32_t x, std::uint32_t y) const { return pixels_[at(x, y)].count; }
  // Of sampleCount, those carried over by reproject() (0 once dropped); the
  // rest were traced for this view.
  std::uint32_t inheritedCount(std::uint32_t x, std::uint32_t y) const { return pixels_[at(x, y)].inherited; }
  std::uint32_t tracedCount(std::uint32_t x, std::uint32_t y) const {
    const Pixel& p = pixels_[at(x, y)];
    return p.count - p.inherited;
  }
  // Whether reproject() started this accumulation (until the next restart).
  bool carriesHistory() const { return carriesHistory_; }
  glm::vec4 colour(std::uint32_t x, std::uint32_t y) const;
  glm::vec3 mean(Channel c, std::uint32_t x, std::uint32_t y) const;
  glm::vec3 variance(Channel c, std::uint32_t x, std::uint32_t y) const;
  float depth(std::uint32_t x, std::uint32_t y) const { return pixels_[at(x, y)].depth; }
  // The instance of the nearest first hit (kNoObject if none hit).
  std::uint32_t object(std::uint32_t x, std::uint32_t y) const { return pixels_[at(x, y)].object; }
  glm::vec3 albedo(std::uint32_t x, std::uint32_t y) const { return pixels_[at(x, y)].albedo; }
  glm::vec3 normal(std::uint32_t x, std::uint32_t y) const { return pixels_[at(x, y)].normal; }
  glm::vec3 emitted(std::uint32_t x, std::uint32_t y) const { return pixels_[at(x, y)].emitted; }
  glm::vec3 firstHalf(std::uint32_t x, std::uint32_t y) const { return pixels_[at(x, y)].firstHalf; }
  std::uint32_t firstHalfCount(std::uint32_t x, std::uint32_t y) const;
  glm::vec3 rangeColour(std::uint32_t x, std::uint32_t y) const { return pixels_[at(x, y)].range; }
  std::uint32_t rangeSamples(std::uint32_t x, std::uint32_t y) const { return pixels_[at(x, y)].rangeCount; }
  float rangeSpread(std::uint32_t x, std::uint32_t y) const;
  float rangeDepth(std::uint32_t x, std::uint32_t y) const;
  // depth: the flash ray's camera-space depth, non-finite on a miss.
  void accumulateRange(std::uint32_t x, std::uint32_t y, const glm::vec3& flash, float depth);

  // Whole images, row-major, for hand-off to filters and compositors.
  std::vector<glm::vec4> colourImage() const;
  std::vector<float> depthImage() const;

 private:
  friend class Renderer;

  std::size_t at(std::uint32_t x, std::uint32_t y) const { return std::size_t(y) * width_ + x; }

  // One pixel's running state, kept together: a sample updates all of it,
  // and samples arrive pixel by pixel.
  struct Pixel {
    std::uint32_t count = 0;
    std::uint32_t inherited = 0;  // of count, carried over by reproject()
    float alpha = 0.0f;
    float depth;
    std::uint32_t object = kNoObject;  // of the nearest hit
    glm::vec3 mean[kChannels]{glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(0.0f)};
    glm::vec3 m2[kChannels]{glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(0.0f)};
    glm::vec3 albedo{0.0f};
    glm::vec3 normal{0.0f};
    glm::vec3 emitted{0.0f};
    glm::vec3 firstHalf{0.0f};  // mean colour - emitted of the first P/2 samples
    glm::vec3 prefix{0.0f};     // the same of the first P samples
    std::uint32_t rangeCount = 0;
    glm::vec3 range{0.0f};
    float rangeM2 = 0.0f;  // sum of squared deviations of the flash samples from their mean
    std::uint32_t rangeHits = 0;
    float rangeDepth = 0.0f;  // mean over the hits
  };

  std::uint32_t width_;
  std::uint32_t height_;
  std::vector<Pixel> pixels_;
  static Pixel emptyPixel();
  static std::uint64_t nextEpoch();
  // Whether the first new sample of a pixel that inherited samples sees what
  // reproject() predicted.
  static bool continues(const Pixel& p, const PixelSample& s);

  std::optional<FrameKey> key_;  // what the accumulated samples were computed for
  std::uint64_t epoch_ = 0;
  bool carriesHistory_ = false;
  // Each instance's placement when key_ was set (Renderer: with a history
  // limit only), for the next reproject().
  std::vector<glm::mat4> placements_;
  std::vector<Pixel> spare_;  // reproject()'s old samples, kept for the next one's memory
};

}  // namespace tsr::embree
