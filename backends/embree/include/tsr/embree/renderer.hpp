#pragma once

#include "tsr/embree/framebuffer.hpp"
#include "tsr/embree/irradiance_field.hpp"
#include "tsr/embree/radiance_filter.hpp"
#include "tsr/embree/render_settings.hpp"
#include "tsr/embree/sampler.hpp"
#include "tsr/embree/scene.hpp"
#include "tsr/embree/vocabulary.hpp"
#include "tsr/embree/whitted_image.hpp"

#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>

namespace tsr::embree {

// How a pass estimates a pixel. Samples of different estimators do not mix
// in one frame buffer: a pass of another one restarts it.
enum class Estimator { Paths, Radiance };

struct PassResult {
  bool completed = false;         // false if cancelled midway
  bool restarted = false;         // accumulation was reset before this pass
  std::uint64_t rays = 0;         // camera, bounce and shadow rays cast in this pass
  std::uint64_t refusedRays = 0;  // rays not traceable (limits.hpp), dropped instead of cast
};

// Progressive path tracer: each renderPass adds samplesPerPass samples to
// every pixel of the region, in parallel over tiles.
class Renderer {
 public:
  explicit Renderer(RenderSettings settings = {});
  ~Renderer();

  const RenderSettings& settings() const { return settings_; }
  void setSettings(const RenderSettings& settings);

  // Commits the scene if needed and restarts accumulation in fb when what it
  // holds was rendered for another scene version, camera, region,
  // image-affecting setting or estimator than a pass of `estimator` would
  // render now; returns whether it restarted. A caller asks this before
  // counting the samples still missing (fb.sampleCount), and drops what it
  // derived from the old samples when it returns true. Passes do the same
  // check themselves.
  bool restartIfStale(Scene& scene, const Camera& camera, const Region& region, FrameBuffer& fb,
                      Estimator estimator = Estimator::Paths);

  // Commits the scene if needed, restarts accumulation in fb when the scene
  // version, camera, region or an image-affecting setting differ from what fb
  // holds, then renders one pass. fb must be region-sized.
  PassResult renderPass(Scene& scene, const Camera& camera, const Region& region, FrameBuffer& fb);

  // Adds `samples` jittered "virtual flash" samples per pixel to fb's range
  // colour (pixel filtering's edge-stopping image, Schwenk 3.3.3): the
  // reflectivity of the first non-specular surface, perfect specular
  // surfaces followed Whitted-style, lit by ambient light and an unoccluded
  // head light. Restarts fb as renderPass does when what it holds is stale.
  PassResult renderFlashPass(Scene& scene, const Camera& camera, const Region& region, FrameBuffer& fb,
                             std::uint32_t samples = 4);

  // The middle renderer of Schwenk's figure 5.6, for the moment the camera
  // rests and before the path tracer's image shows much: one Whitted-style
  // sample per pixel through its centre. Perfect specular surfaces (mirrors,
  // glass, smooth metallic-roughness) are followed as a ray tree up to
  // maxDepth, sharp; other surfaces are lit straight from the point, spot and
  // directional lights and from the centroids of emitter triangles, each
  // behind one shadow ray, so shadows are hard; the environment lights them
  // from their normal's direction. No indirect light. A second call for the
  // same scene, camera, region and settings is free (nothing is traced).
  // image must be region-sized.
  PassResult renderWhitted(Scene& scene, const Camera& camera, const Region& region, WhittedImage& image);

  // Radiance filtering (radiance_filter.hpp): traces one path per pixel
  // (samplesPerPass is ignored), accumulating it into fb as renderPass does
  // and storing its radiance sample in acc; then filters the samples into
  // acc's indirect, in parallel and deterministically. acc restarts with fb.
  // The image is acc.radiance(fb, x, y). A cancelled pass leaves acc as it
  // was (its samples still reach fb).
  PassResult renderRadiancePass(Scene& scene, const Camera& camera, const Region& region, FrameBuffer& fb,
                                RadianceAccumulator& acc, const RadianceFilterSettings& filter = {});

  // Direct light per pixel, indirect light from a photon reconstruction
  // (photon_sequence.hpp): paths are traced as in renderPass through
  // perfect specular surfaces; at the first Diffuse surface they take
  // direct light by light sampling and add albedo / pi x field.at(...) as
  // Indirect, then end. Other materials trace their indirect light as usual.
  // The field must fit the scene (IrradianceField::fits; throws otherwise);
  // a new field restarts accumulation in fb.
  PassResult renderWithIrradiance(Scene& scene, const Camera& camera, const Region& region, FrameBuffer& fb,
                                  const IrradianceField& field);

  // Thread-safe. Stops the running pass at the next tile row, or the next
  // pass if none runs; that pass returns completed = false.
  void requestCancel() { cancel_.store(true, std::memory_order_relaxed); }

  std::uint64_t totalRays() const { return totalRays_; }

 private:
  struct Arena;
  // Calls perPixel(tracer, x, y, fullImageX, fullImageY) over parallel
  // tiles of the region (after the caller's staleness check).
  template <class PerPixel>
  PassResult runTiles(Scene& scene, const Region& region, PerPixel&& perPixel);
  // Validates, commits, restarts fb if stale for `estimator` (FrameKey's;
  // none: the pass joins whichever estimator fb holds, as flash samples do).
  bool restartIfStale(Scene& scene, const Camera& camera, const Region& region, FrameBuffer& fb,
                      std::optional<std::uint64_t> estimator);
  // Validates, commits, and replaces `held` by the key of an image of
  // `estimator` rendered now; returns whether it differed.
  bool rekey(Scene& scene, const Camera& camera, const Region& region, std::uint32_t width, std::uint32_t height,
             std::optional<FrameKey>& held, std::optional<std::uint64_t> estimator);
  // Path samples for renderPass; with a field, for renderWithIrradiance.
  PassResult renderPaths(Scene& scene, const Camera& camera, const Region& region, FrameBuffer& fb,
                         const IrradianceField* field);
  RenderSettings settings_;
  std::unique_ptr<Arena> arena_;
  std::atomic<bool> cancel_{false};
  std::uint64_t totalRays_ = 0;
};

}  // namespace tsr::embree
