#include "tsr/embree/renderer.hpp"

#include "filters/radiance_filter_step.hpp"
#include "scene/instance_motion.hpp"
#include "scene/streamed_geometry.hpp"
#include "tracing/tracer.hpp"
#include "tsr/backend/validate.hpp"
#include "tsr/embree/error.hpp"

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/partitioner.h>
#include <oneapi/tbb/task_arena.h>
#include <spdlog/spdlog.h>

#include <limits>
#include <optional>
#include <string>

namespace tsr::embree {

struct Renderer::Arena {
  explicit Arena(int threads) : arena(threads > 0 ? threads : tbb::task_arena::automatic) {}
  tbb::task_arena arena;
};

namespace {

// FrameKey::estimator of radiance passes (plain paths: 0, an irradiance
// field: a hash of its uid).
constexpr std::uint64_t kRadianceEstimator = 0x3C6EF372FE94F82Bull;
// ... and of a WhittedImage.
constexpr std::uint64_t kWhittedEstimator = 0xA54FF53A5F1D36F1ull;

std::uint64_t estimatorKey(Estimator e) {
  switch (e) {
    case Estimator::Paths:
      return 0;
    case Estimator::Radiance:
      return kRadianceEstimator;
  }
  return 0;
}

}  // namespace

Renderer::Renderer(RenderSettings settings) { setSettings(settings); }
Renderer::~Renderer() = default;

void Renderer::setSettings(const RenderSettings& settings) {
  if (settings.samplesPerPass == 0) throw Error("samplesPerPass must be at least 1");
  if (settings.tileSize == 0) throw Error("tileSize must be at least 1");
  if (settings.threads < 0) throw Error("threads must be >= 0 (0 = all)");
  if (!arena_ || settings.threads != settings_.threads) arena_ = std::make_unique<Arena>(settings.threads);
  settings_ = settings;
}

bool Renderer::restartIfStale(Scene& scene, const Camera& camera, const Region& region, FrameBuffer& fb,
                              Estimator estimator) {
  return restartIfStale(scene, camera, region, fb, estimatorKey(estimator));
}

bool Renderer::rekey(Scene& scene, const Camera& camera, const Region& region, std::uint32_t width,
                     std::uint32_t height, std::optional<FrameKey>& held, std::optional<std::uint64_t> estimator) {
  backend::validate<Error>(camera);
  backend::validate<Error>(region);
  if (width != region.regionWidth() || height != region.regionHeight()) {
    throw Error("frame buffer is " + std::to_string(width) + "x" + std::to_string(height) + " but the region is " +
                std::to_string(region.regionWidth()) + "x" + std::to_string(region.regionHeight()));
  }
  scene.commit();
  const FrameKey key{scene.uid(),
                     scene.version(),
                     camera,
                     region,
                     imageSettings(settings_),
                     estimator.value_or(held ? held->estimator : 0),
                     scene.appearanceVersion()};
  if (held && *held == key) return false;
  held = key;
  return true;
}

namespace {

// Whether samples taken for `then` may be reprojected to `now`: the same
// scene looking the same (instances may have moved), the same settings,
// plain path samples on both sides.
bool historyCarries(const FrameKey& then, const FrameKey& now) {
  return then.sceneUid == now.sceneUid && then.sceneAppearance == now.sceneAppearance &&
         then.settings == now.settings && then.estimator == 0 && now.estimator == 0 &&
         then.region.width == now.region.width && then.region.height == now.region.height;
}

// Each instance's placement (world from object), by instance index.
std::vector<glm::mat4> placements(const Scene& scene) {
  const SceneState& state = scene.state();
  std::vector<glm::mat4> out(state.views.size());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = state.views[i].transform;
  return out;
}

}  // namespace

bool Renderer::restartIfStale(Scene& scene, const Camera& camera, const Region& region, FrameBuffer& fb,
                              std::optional<std::uint64_t> estimator) {
  const std::optional<FrameKey> held = fb.key_;
  std::optional<FrameKey> key = held;
  if (!rekey(scene, camera, region, fb.width(), fb.height(), key, estimator)) return false;
  if (settings_.historyLimit > 0) {
    std::vector<glm::mat4> now = placements(scene);
    if (held && historyCarries(*held, *key)) {
      const Reprojection r{held->camera, camera, held->region, region, fb.placements_, now, settings_.historyLimit};
      arena_->arena.execute([&] { fb.reproject(r); });
    } else {
      fb.reset();
    }
    fb.placements_ = std::move(now);
  } else {
    fb.reset();
    fb.placements_.clear();
  }
  fb.key_ = key;
  return true;
}

template <class PerPixel>
PassResult Renderer::runTiles(Scene& scene, const Region& region, PerPixel&& perPixel) {
  PassResult result;

  const SceneState& state = scene.state();
  const RenderSettings settings = settings_;
  const std::uint32_t ts = settings.tileSize;
  const std::uint32_t rw = region.regionWidth(), rh = region.regionHeight();
  const std::uint32_t tilesX = (rw + ts - 1) / ts, tilesY = (rh + ts - 1) / ts;
  std::vector<std::uint64_t> tileRays(std::size_t(tilesX) * tilesY, 0);
  std::vector<std::uint64_t> tileRefused(tileRays.size(), 0);
  std::atomic<bool> cancelled{false};

  auto renderTile = [&](std::size_t tile) {
    Tracer tracer{state, settings};
    std::uint32_t tx = std::uint32_t(tile % tilesX), ty = std::uint32_t(tile / tilesX);
    std::uint32_t xb = tx * ts, xe = std::min(rw, xb + ts);
    std::uint32_t yb = ty * ts, ye = std::min(rh, yb + ts);
    for (std::uint32_t y = yb; y < ye; ++y) {
      if (cancel_.load(std::memory_order_relaxed)) {
        cancelled.store(true, std::memory_order_relaxed);
        break;
      }
      for (std::uint32_t x = xb; x < xe; ++x) perPixel(tracer, x, y, region.x0 + x, region.y0 + y);
    }
    tileRays[tile] = tracer.rays;
    tileRefused[tile] = tracer.refused;
  };

  arena_->arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, tileRays.size(), 1),
        [&](const tbb::blocked_range<std::size_t>& r) {
          for (std::size_t t = r.begin(); t != r.end(); ++t) renderTile(t);
        },
        tbb::simple_partitioner());
  });

  for (auto r : tileRays) result.rays += r;
  for (auto r : tileRefused) result.refusedRays += r;
  if (result.refusedRays)
    spdlog::warn("tsr::embree: {} rays could not be traced (coordinates beyond {} or NaN) and were dropped",
                 result.refusedRays, kMaxRayComponent);
  if (state.streamed) {
    const TraceMemoryUse u = state.streamed->use();
    spdlog::debug("tsr::embree: {} of {} clusters of the merged scene held ({:.0f} MB), {} built, {} dropped so far",
                  u.built, u.clusters, double(u.heldBytes) * 1e-6, u.builds, u.evictions);
  }
  totalRays_ += result.rays;
  result.completed = !cancelled.load();
  if (!result.completed) cancel_.store(false, std::memory_order_relaxed);
  return result;
}

namespace {

// Where camera rays start and how they are turned into world space.
struct Eye {
  glm::vec3 position;
  glm::vec3 forward;
  glm::mat3 rotation;
  explicit Eye(const glm::mat4& cameraToWorld)
      : position(cameraToWorld[3]), forward(glm::normalize(-glm::vec3(cameraToWorld[2]))), rotation(cameraToWorld) {}
};

// Where the camera is over the frame interval: still, or moving as moving
// instances do (InstanceMotion: turning, not shrinking, mid-frame).
class CameraPath {
 public:
  explicit CameraPath(const Camera& c) : still_(c.cameraToWorld) {
    if (c.cameraToWorldAtEnd) motion_.emplace(c.cameraToWorld, *c.cameraToWorldAtEnd);
  }
  Eye at(float t) const { return motion_ && t != 0.0f ? Eye(motion_->at(t)) : still_; }

 private:
  Eye still_;
  std::optional<InstanceMotion> motion_;
};

// A camera ray, the time it is traced at, and the eye it leaves (where
// depth is measured from).
struct CameraRay {
  glm::vec3 origin, direction;
  float time;
  glm::vec3 eyePosition, forward;
};

// The middle of the shutter: the one instant of a pass that has one ray a pixel.
float shutterMiddle(const Camera& camera) { return 0.5f * (camera.shutterOpen + camera.shutterClose); }

// The point at `jitter` in full-image pixel (px, py) on the window, in camera space.
glm::vec3 windowPoint(const Camera& camera, const Region& region, std::uint32_t px, std::uint32_t py,
                      const glm::vec2& jitter) {
  const float cx = camera.left + (camera.right - camera.left) * ((float(px) + jitter.x) / float(region.width));
  const float cy = camera.top - (camera.top - camera.bottom) * ((float(py) + jitter.y) / float(region.height));
  return {cx, cy, -camera.near};
}

// A camera ray through a jittered point of full-image pixel (px, py); with
// a lens, from a uniform point of the aperture towards where the pinhole
// ray meets the plane in focus. With the shutter open over an interval,
// the ray's time is uniform in it. The Sobol sampler draws the lens' and
// the time's sets whether they are used or not, so a render with and
// without a lens or shutter differ by the effect alone, not by their
// noise; the independent sampler draws them only when used (its images
// stay as they were before lenses and shutters).
CameraRay cameraRay(const Camera& camera, const CameraPath& path, const Region& region, std::uint32_t px,
                    std::uint32_t py, Sampler& sampler) {
  const glm::vec3 pinhole = windowPoint(camera, region, px, py, sampler.uniform2());
  const bool reserve = sampler.kind() == SamplerKind::Sobol;  // see above: Sobol keeps the sets unused
  glm::vec2 u(0.0f);
  if (camera.apertureRadius > 0.0f)
    u = sampler.uniform2();
  else if (reserve)
    sampler.skip(2);
  float time = camera.shutterOpen;
  if (camera.shutterClose > camera.shutterOpen)
    time += (camera.shutterClose - camera.shutterOpen) * sampler.uniform();
  else if (reserve)
    sampler.skip(1);
  const Eye eye = path.at(time);
  if (camera.apertureRadius <= 0.0f)
    return {eye.position, glm::normalize(eye.rotation * pinhole), time, eye.position, eye.forward};
  const float r = camera.apertureRadius * std::sqrt(u.x), phi = 2.0f * kPi * u.y;
  const glm::vec3 lens(r * std::cos(phi), r * std::sin(phi), 0.0f);
  const glm::vec3 focus = pinhole * (camera.focusDistance / camera.near);
  return {eye.position + eye.rotation * lens, glm::normalize(eye.rotation * (focus - lens)), time, eye.position,
          eye.forward};
}

// The flash samples' random stream, apart from the path samples'.
constexpr std::uint64_t kFlashStream = 0x6A09E667F3BCC909ull;

}  // namespace

namespace {
// A pass's camera samples: sample `first + s` of full-image pixel (px, py)
// is the same sampler and ray in whatever pass, tile or node traces it.
struct CameraSamples {
  const Camera& camera;
  const CameraPath path;
  const Region& region;
  std::uint64_t seed;
  SamplerKind kind;

  // trace(sampler, ray) for `count` samples from `first` on, the tracer's
  // time set to each ray's (the shutter).
  template <class Trace>
  void each(Tracer& tracer, std::uint32_t px, std::uint32_t py, std::uint32_t first, std::uint32_t count,
            Trace trace) const {
    const std::uint64_t pixelKey = Rng::pixelKey(seed, px, py);
    for (std::uint32_t s = 0; s < count; ++s) {
      Sampler sampler(kind, pixelKey, first + s);
      const CameraRay ray = cameraRay(camera, path, region, px, py, sampler);
      tracer.time = ray.time;
      trace(sampler, ray);
    }
  }
};
}  // namespace

PassResult Renderer::renderPass(Scene& scene, const Camera& camera, const Region& region, FrameBuffer& fb) {
  return renderPaths(scene, camera, region, fb, nullptr);
}

PassResult Renderer::renderPaths(Scene& scene, const Camera& camera, const Region& region, FrameBuffer& fb,
                                 const IrradianceField* field) {
  const CameraSamples samples{camera, CameraPath(camera), region, settings_.seed, settings_.sampler};
  const std::uint32_t count = settings_.samplesPerPass;
  const bool restarted = restartIfStale(scene, camera, region, fb, field ? splitmix64(field->uid()) : 0);
  PassResult result = runTiles(
      scene, region, [&](Tracer& tracer, std::uint32_t x, std::uint32_t y, std::uint32_t px, std::uint32_t py) {
        tracer.irradiance = field;
        samples.each(tracer, px, py, fb.sampleCount(x, y), count, [&](Sampler& sampler, const CameraRay& ray) {
          fb.accumulate(x, y, tracer.tracePath(sampler, ray.origin, ray.direction, ray.eyePosition, ray.forward));
        });
      });
  result.restarted = restarted;
  return result;
}

PassResult Renderer::renderWithIrradiance(Scene& scene, const Camera& camera, const Region& region, FrameBuffer& fb,
                                          const IrradianceField& field) {
  scene.commit();  // the element check reads the committed instances
  if (field.empty() || !field.fits(scene))
    throw Error("the irradiance field was reconstructed on other instances or meshes than this scene has");
  return renderPaths(scene, camera, region, fb, &field);
}

PassResult Renderer::renderRadiancePass(Scene& scene, const Camera& camera, const Region& region, FrameBuffer& fb,
                                        RadianceAccumulator& acc, const RadianceFilterSettings& filter) {
  filter.validate();
  if (acc.width() != region.regionWidth() || acc.height() != region.regionHeight()) {
    throw Error("radiance accumulator is " + std::to_string(acc.width()) + "x" + std::to_string(acc.height()) +
                " but the region is " + std::to_string(region.regionWidth()) + "x" +
                std::to_string(region.regionHeight()));
  }
  const CameraSamples samples{camera, CameraPath(camera), region, settings_.seed, settings_.sampler};
  // Angle of one pixel on the axis; off the axis it shrinks with cos^1.5.
  const float pixelAngle = std::sqrt((camera.right - camera.left) / float(region.width) * (camera.top - camera.bottom) /
                                     float(region.height)) /
                           camera.near;
  const bool restarted = restartIfStale(scene, camera, region, fb, kRadianceEstimator);
  PassResult result = runTiles(
      scene, region, [&](Tracer& tracer, std::uint32_t x, std::uint32_t y, std::uint32_t px, std::uint32_t py) {
        samples.each(tracer, px, py, fb.sampleCount(x, y), 1, [&](Sampler& sampler, const CameraRay& ray) {
          RadianceSample& record = acc.samples_[acc.at(x, y)];
          record = RadianceSample{};
          PixelSample sample =
              tracer.tracePath(sampler, ray.origin, ray.direction, ray.eyePosition, ray.forward, &record);
          const float c = glm::dot(ray.direction, ray.forward);
          record.pixelAngle = pixelAngle * c * std::sqrt(c);
          record.unfiltered = sample.indirect - sample.caustic;
          fb.accumulate(x, y, sample);
        });
      });
  result.restarted = restarted;
  if (result.completed) arena_->arena.execute([&] { RadianceFilterStep::run(fb, acc, filter); });
  return result;
}

PassResult Renderer::renderWhitted(Scene& scene, const Camera& camera, const Region& region, WhittedImage& image) {
  const bool restarted = rekey(scene, camera, region, image.width(), image.height(), image.key_, kWhittedEstimator);
  if (!restarted && image.complete_) return PassResult{true, false, 0, 0};
  image.complete_ = false;
  // One instant, the shutter's middle: a Whitted frame is sharp everywhere.
  const float time = shutterMiddle(camera);
  const Eye eye = CameraPath(camera).at(time);
  const std::uint32_t width = image.width();
  PassResult result = runTiles(
      scene, region, [&](Tracer& tracer, std::uint32_t x, std::uint32_t y, std::uint32_t px, std::uint32_t py) {
        // Through the pixel's centre and the lens'.
        const glm::vec3 dir = glm::normalize(eye.rotation * windowPoint(camera, region, px, py, glm::vec2(0.5f)));
        tracer.time = time;
        const PixelSample s = tracer.traceWhitted(eye.position, dir, eye.position, eye.forward);
        const std::size_t i = std::size_t(y) * width + x;
        image.colour_[i] = glm::vec4(s.direct + s.indirect, s.hit ? 1.0f : 0.0f);
        image.depth_[i] = s.hit ? s.depth : std::numeric_limits<float>::infinity();
        image.albedo_[i] = s.albedo;
        image.normal_[i] = s.normal;
      });
  result.restarted = restarted;
  image.complete_ = result.completed;
  return result;
}

PassResult Renderer::renderFlashPass(Scene& scene, const Camera& camera, const Region& region, FrameBuffer& fb,
                                     std::uint32_t samples) {
  const CameraSamples flashSamples{camera, CameraPath(camera), region, settings_.seed ^ kFlashStream,
                                   settings_.sampler};
  const bool restarted = restartIfStale(scene, camera, region, fb, std::nullopt);
  PassResult result = runTiles(
      scene, region, [&](Tracer& tracer, std::uint32_t x, std::uint32_t y, std::uint32_t px, std::uint32_t py) {
        flashSamples.each(tracer, px, py, fb.rangeSamples(x, y), samples, [&](Sampler&, const CameraRay& ray) {
          float distance = kInf;
          const glm::vec3 flash = tracer.traceFlash(ray.origin, ray.direction, ray.eyePosition, distance);
          fb.accumulateRange(x, y, flash, distance * glm::dot(ray.direction, ray.forward));
        });
      });
  result.restarted = restarted;
  return result;
}

}  // namespace tsr::embree
