#include "tsr/embree/renderer.hpp"

#include "filters/radiance_filter_step.hpp"
#include "tracing/delta_lights.hpp"
#include "tracing/tracer.hpp"
#include "tsr/embree/error.hpp"

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/partitioner.h>
#include <oneapi/tbb/task_arena.h>
#include <spdlog/spdlog.h>

#include <string>
#include <type_traits>

namespace tsr::embree {

struct Renderer::Arena {
  explicit Arena(int threads) : arena(threads > 0 ? threads : tbb::task_arena::automatic) {}
  tbb::task_arena arena;
};

namespace {

std::uint64_t settingsHash(const RenderSettings& s) {
  std::uint64_t h = splitmix64(s.seed);
  h = splitmix64(h ^ s.maxDepth);
  h = splitmix64(h ^ s.rouletteDepth);
  return splitmix64(h ^ std::uint64_t(s.lightSampling));
}

// FrameBuffer::Key::estimator of radiance passes (plain paths: 0, an
// irradiance field: a hash of its uid).
constexpr std::uint64_t kRadianceEstimator = 0x3C6EF372FE94F82Bull;

}  // namespace

PixelSample Tracer::tracePath(Rng& rng, glm::vec3 org, glm::vec3 dir, const glm::vec3& camPos, const glm::vec3& forward,
                              RadianceSample* record) {
  PixelSample out;
  const Environment& env = scene.environment;
  const bool envActive = !env.isBlack();
  const LightSampling mode = settings.lightSampling;
  // Classification relative to the first non-specular vertex, as pixel
  // filtering needs it: direct is light reaching that vertex straight from
  // an emitter (or emission seen through perfect specular chains); a path
  // that passes a specular surface after a non-specular one is a caustic,
  // the hardest to sample, and is indirect however few vertices it has.
  std::uint32_t nonSpecular = 0;      // non-specular scattering vertices so far
  bool specularAfterDiffuse = false;  // a specular vertex followed one of them
  // With a radiance record, throughput restarts at 1 after the first
  // non-specular vertex, so that indirect contributions arrive as the
  // incident radiance there; scale carries the weight from the eye to that
  // vertex's outgoing ray (exactly 1 otherwise).
  glm::vec3 scale(1.0f);
  float pathLength = 0.0f;
  std::uint8_t mask = 0;
  auto add = [&](const glm::vec3& c, std::uint32_t nonSpecularVertices) {
    if (!finite(c)) return;  // a NaN sample would poison the running mean forever
    const glm::vec3 v = c * scale;
    if (specularAfterDiffuse || nonSpecularVertices > 1) {
      out.indirect += v;
      if (specularAfterDiffuse) out.caustic += v;
      if (record && !specularAfterDiffuse) record->radiance += c;
    } else {
      out.direct += v;
    }
  };
  // MIS weight for an emitter reached by BSDF sampling.
  auto bsdfHitWeight = [mode](float bsdfPdf, float lightPdf) {
    if (mode == LightSampling::BsdfOnly) return 1.0f;
    if (mode == LightSampling::LightOnly) return 0.0f;
    return powerHeuristic(bsdfPdf, lightPdf);
  };
  auto lightSampleWeight = [mode](float lightPdf, float bsdfPdf) {
    return mode == LightSampling::LightOnly ? 1.0f : powerHeuristic(lightPdf, bsdfPdf);
  };

  glm::vec3 throughput(1.0f);
  float prevPdf = 0.0f;
  bool prevDelta = true;

  for (std::uint32_t depth = 0;; ++depth) {
    if (!traceable(org, dir, kInf)) {
      ++refused;
      break;
    }
    RTCRayHit rh;
    if (!intersect(org, dir, rh)) {
      if (envActive) {
        float w = (depth == 0 || prevDelta) ? 1.0f : bsdfHitWeight(prevPdf, env.pdf(dir));
        add(throughput * env.radiance(dir) * w, nonSpecular);
      }
      break;
    }
    SurfaceHit h;
    if (!surface(org, dir, rh, h)) break;
    if (nonSpecular == 0) pathLength += rh.ray.tfar;
    const ResolvedMaterial& mat = *h.instance->material;
    glm::vec3 base = baseColour(mat, h.uv);
    if (depth == 0) {
      out.hit = true;
      out.depth = glm::dot(h.p - camPos, forward);
      out.albedo = base;
      out.normal = glm::dot(h.ns, dir) > 0.0f ? -h.ns : h.ns;
    }
    if (mat.material.isEmissive() && glm::dot(h.faceNormal, dir) < 0.0f) {
      float w = (depth == 0 || prevDelta) ? 1.0f : bsdfHitWeight(prevPdf, emitterPdf(h, dir, rh.ray.tfar));
      add(throughput * emission(mat, h.uv) * w, nonSpecular);
    }
    if (depth >= settings.maxDepth) break;

    const glm::vec3 wo = -dir;
    const bool front = glm::dot(wo, h.ng) > 0.0f;
    const glm::vec3 ng = front ? h.ng : -h.ng;
    const Frame frame(front ? h.ns : -h.ns);
    const glm::vec3 woL = frame.toLocal(wo);
    if (woL.z <= 1e-6f) break;  // shading normal faces away from the viewer: no consistent answer
    Bsdf bsdf;
    bsdf.type = mat.material.type;
    bsdf.colour = base;
    bsdf.alpha = std::max(1e-3f, mat.material.roughness * mat.material.roughness);
    bsdf.eta = front ? mat.material.ior : 1.0f / mat.material.ior;

    const float eps = rayEpsilon(h.p);
    auto spawn = [&](const glm::vec3& w) { return h.p + ng * (glm::dot(w, ng) > 0.0f ? eps : -eps); };
    // f * |cos| for a world direction, zero when shading and geometry
    // disagree; and the BSDF's sampling density where MIS needs it.
    auto evalWorld = [&](const glm::vec3& wi, float* pdf) {
      glm::vec3 wiL = frame.toLocal(wi);
      if ((glm::dot(wi, ng) > 0.0f) != (wiL.z > 0.0f)) {
        if (pdf) *pdf = 0.0f;
        return glm::vec3(0.0f);
      }
      if (pdf) *pdf = bsdf.pdf(woL, wiL);
      return bsdf.eval(woL, wiL);
    };

    // Random numbers are drawn in a fixed order: emitter, environment, BSDF,
    // roulette. The continuation is computed before the shadow rays are
    // traced: it does not depend on them, and its chain of square roots,
    // divisions and sincos then runs while Embree traverses, instead of
    // after it (out-of-order execution does not reach past the mispredicted
    // branches of a traversal into the code that follows the call).
    const bool nextEvent = !bsdf.isDelta();
    const bool sampleEmitters = nextEvent && !scene.emitters.empty() && mode != LightSampling::BsdfOnly;
    const bool sampleEnvironment = nextEvent && envActive && mode != LightSampling::BsdfOnly;
    float uSelect = 0.0f;
    glm::vec2 uPoint(0.0f), uEnvironment(0.0f);
    if (sampleEmitters) {
      uSelect = rng.uniform();
      uPoint = rng.uniform2();
    }
    if (sampleEnvironment) uEnvironment = rng.uniform2();
    const glm::vec2 u = rng.uniform2();
    const float uLobe = rng.uniform();
    BsdfSample bs;
    glm::vec3 nextDir(0.0f);
    bool continues = bsdf.sample(woL, u, uLobe, bs);
    if (continues) {
      nextDir = glm::normalize(frame.toWorld(bs.wi));
      continues = (glm::dot(nextDir, ng) > 0.0f) == (bs.wi.z > 0.0f);
    }
    const bool recordHere = record && nextEvent && nonSpecular == 0;
    const bool fromField = irradiance && nonSpecular == 0 && bsdf.type == MaterialType::Diffuse;
    if (recordHere) {
      RadianceSample& r = *record;
      r.valid = true;
      r.position = h.p;
      r.normal = frame.n;
      r.wo = wo;
      r.wi = continues ? nextDir : glm::vec3(0.0f);
      r.pdf = continues ? bs.pdf : 0.0f;
      r.throughput = throughput;
      r.distance = pathLength;
      r.type = bsdf.type;
      r.colour = bsdf.colour;
      r.alpha = bsdf.alpha;
      r.eta = bsdf.eta;
    }
    glm::vec3 nextThroughput = throughput;
    glm::vec3 nextScale = scale;
    if (continues) {
      if (recordHere) {
        nextScale = throughput * bs.weight;
        nextThroughput = glm::vec3(1.0f);
      } else {
        nextThroughput *= bs.weight;
      }
      if (depth + 1 >= settings.rouletteDepth) {
        float q = std::min(maxComponent(nextThroughput * nextScale), 0.95f);
        if (!(q > 0.0f) || rng.uniform() >= q)
          continues = false;
        else
          nextThroughput /= q;
      }
    }
    const glm::vec3 nextOrg = spawn(nextDir);

    if (nextEvent) {
      for (const Light& light : scene.activeLights) {
        LightArrival a;
        if (!lightArriving(light, h.p, a)) continue;
        glm::vec3 f = evalWorld(a.wi, nullptr);  // delta lights: no MIS
        if (maxComponent(f) <= 0.0f) continue;
        if (!occluded(spawn(a.wi), a.wi, a.tfar)) add(throughput * f * a.li, nonSpecular + 1);
      }
      if (sampleEmitters) {
        EmitterSample es;
        if (sampleEmitter(h.p, uSelect, uPoint, es)) {
          float bsdfPdf;
          glm::vec3 f = evalWorld(es.wi, &bsdfPdf);
          if (maxComponent(f) > 0.0f) {
            glm::vec3 o = spawn(es.wi);
            float dist = glm::length(es.point - o);
            if (!occluded(o, es.wi, dist - rayEpsilon(es.point))) {
              const float w = fromField ? 1.0f : lightSampleWeight(es.pdf, bsdfPdf);
              add(throughput * f * es.radiance * (w / es.pdf), nonSpecular + 1);
            }
          }
        }
      }
      if (sampleEnvironment) {
        Environment::Sample es = env.sample(uEnvironment);
        if (es.pdf > 0.0f) {
          float bsdfPdf;
          glm::vec3 f = evalWorld(es.direction, &bsdfPdf);
          if (maxComponent(f) > 0.0f && !occluded(spawn(es.direction), es.direction, kInf)) {
            const float w = fromField ? 1.0f : lightSampleWeight(es.pdf, bsdfPdf);
            add(throughput * f * es.radiance * (w / es.pdf), nonSpecular + 1);
          }
        }
      }
    }
    if (fromField) {
      const auto inst = std::uint32_t(h.instance - scene.views.data());
      add(throughput * base * kInvPi * irradiance->at(inst, h.prim, rh.hit.u, rh.hit.v), nonSpecular + 2);
      break;
    }

    if (!continues) break;
    if (bs.delta && nonSpecular == 0) {
      mask |= kMaskSpecular;
      if (bsdf.type == MaterialType::Glass) mask |= kMaskReflectRefract;
    }
    if (bs.delta)
      specularAfterDiffuse = specularAfterDiffuse || nonSpecular > 0;
    else
      ++nonSpecular;
    throughput = nextThroughput;
    scale = nextScale;
    prevPdf = bs.pdf;
    prevDelta = bs.delta;
    org = nextOrg;
    dir = nextDir;
  }
  if (record) record->mask = mask;
  return out;
}

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
  return restartIfStale(scene, camera, region, fb, estimator == Estimator::Radiance ? kRadianceEstimator : 0);
}

bool Renderer::restartIfStale(Scene& scene, const Camera& camera, const Region& region, FrameBuffer& fb,
                              std::optional<std::uint64_t> estimator) {
  camera.validate();
  region.validate();
  if (fb.width() != region.regionWidth() || fb.height() != region.regionHeight()) {
    throw Error("frame buffer is " + std::to_string(fb.width()) + "x" + std::to_string(fb.height()) +
                " but the region is " + std::to_string(region.regionWidth()) + "x" +
                std::to_string(region.regionHeight()));
  }
  scene.commit();
  const std::uint64_t held = fb.key_ ? fb.key_->estimator : 0;
  FrameBuffer::Key key{scene.uid(), scene.version(), camera, region, settingsHash(settings_), estimator.value_or(held)};
  if (fb.key_ && *fb.key_ == key) return false;
  fb.reset();
  fb.key_ = key;
  return true;
}

template <class PerPixel>
PassResult Renderer::runTiles(Scene& scene, const Camera& camera, const Region& region, FrameBuffer& fb,
                              PerPixel&& perPixel, std::optional<std::uint64_t> estimator) {
  PassResult result;
  result.restarted = restartIfStale(scene, camera, region, fb, estimator);

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
  totalRays_ += result.rays;
  result.completed = !cancelled.load();
  if (!result.completed) cancel_.store(false, std::memory_order_relaxed);
  return result;
}

namespace {

// A camera ray through a jittered point of full-image pixel (px, py).
glm::vec3 cameraRay(const Camera& camera, const glm::mat3& camRot, const Region& region, std::uint32_t px,
                    std::uint32_t py, const glm::vec2& jitter) {
  float cx = camera.left + (camera.right - camera.left) * ((float(px) + jitter.x) / float(region.width));
  float cy = camera.top - (camera.top - camera.bottom) * ((float(py) + jitter.y) / float(region.height));
  return glm::normalize(camRot * glm::vec3(cx, cy, -camera.near));
}

// Where camera rays start and how they are turned into world space.
struct Eye {
  glm::vec3 position;
  glm::vec3 forward;
  glm::mat3 rotation;
  explicit Eye(const Camera& c)
      : position(c.cameraToWorld[3]),
        forward(glm::normalize(-glm::vec3(c.cameraToWorld[2]))),
        rotation(c.cameraToWorld) {}
};

// The flash samples' random stream, apart from the path samples'.
constexpr std::uint64_t kFlashStream = 0x6A09E667F3BCC909ull;

}  // namespace

PassResult Renderer::renderPass(Scene& scene, const Camera& camera, const Region& region, FrameBuffer& fb) {
  return renderPaths(scene, camera, region, fb, nullptr);
}

PassResult Renderer::renderPaths(Scene& scene, const Camera& camera, const Region& region, FrameBuffer& fb,
                                 const IrradianceField* field) {
  const Eye eye(camera);
  const std::uint64_t seed = settings_.seed;
  const std::uint32_t samples = settings_.samplesPerPass;
  return runTiles(
      scene, camera, region, fb,
      [&](Tracer& tracer, std::uint32_t x, std::uint32_t y, std::uint32_t px, std::uint32_t py) {
        tracer.irradiance = field;
        const std::uint64_t pixelKey = Rng::pixelKey(seed, px, py);
        const std::uint32_t firstSample = fb.sampleCount(x, y);
        for (std::uint32_t s = 0; s < samples; ++s) {
          Rng rng(pixelKey, firstSample + s);
          glm::vec3 dir = cameraRay(camera, eye.rotation, region, px, py, rng.uniform2());
          fb.accumulate(x, y, tracer.tracePath(rng, eye.position, dir, eye.position, eye.forward));
        }
      },
      field ? splitmix64(field->uid()) : 0);
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
  const Eye eye(camera);
  const std::uint64_t seed = settings_.seed;
  // Angle of one pixel on the axis; off the axis it shrinks with cos^1.5.
  const float pixelAngle = std::sqrt((camera.right - camera.left) / float(region.width) * (camera.top - camera.bottom) /
                                     float(region.height)) /
                           camera.near;
  PassResult result = runTiles(
      scene, camera, region, fb,
      [&](Tracer& tracer, std::uint32_t x, std::uint32_t y, std::uint32_t px, std::uint32_t py) {
        Rng rng(Rng::pixelKey(seed, px, py), fb.sampleCount(x, y));
        glm::vec3 dir = cameraRay(camera, eye.rotation, region, px, py, rng.uniform2());
        RadianceSample& record = acc.samples_[acc.at(x, y)];
        record = RadianceSample{};
        PixelSample sample = tracer.tracePath(rng, eye.position, dir, eye.position, eye.forward, &record);
        const float c = glm::dot(dir, eye.forward);
        record.pixelAngle = pixelAngle * c * std::sqrt(c);
        record.unfiltered = sample.indirect - sample.caustic;
        fb.accumulate(x, y, sample);
      },
      kRadianceEstimator);
  if (result.completed) arena_->arena.execute([&] { RadianceFilterStep::run(fb, acc, filter); });
  return result;
}

PassResult Renderer::renderFlashPass(Scene& scene, const Camera& camera, const Region& region, FrameBuffer& fb,
                                     std::uint32_t samples) {
  const Eye eye(camera);
  const std::uint64_t seed = settings_.seed ^ kFlashStream;
  return runTiles(
      scene, camera, region, fb,
      [&](Tracer& tracer, std::uint32_t x, std::uint32_t y, std::uint32_t px, std::uint32_t py) {
        const std::uint64_t pixelKey = Rng::pixelKey(seed, px, py);
        const std::uint32_t first = fb.rangeSamples(x, y);
        for (std::uint32_t s = 0; s < samples; ++s) {
          Rng rng(pixelKey, first + s);
          glm::vec3 dir = cameraRay(camera, eye.rotation, region, px, py, rng.uniform2());
          float distance = kInf;
          const glm::vec3 flash = tracer.traceFlash(eye.position, dir, eye.position, distance);
          fb.accumulateRange(x, y, flash, distance * glm::dot(dir, eye.forward));
        }
      },
      std::nullopt);
}

}  // namespace tsr::embree
