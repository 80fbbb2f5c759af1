#include "tsr/embree/renderer.hpp"

#include "bsdf.hpp"
#include "scene_state.hpp"
#include "tsr/embree/error.hpp"
#include "tsr/embree/limits.hpp"
#include "tsr/embree/rng.hpp"
#include "tsr/embree/sampling.hpp"

#include <glm/geometric.hpp>
#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/partitioner.h>
#include <oneapi/tbb/task_arena.h>
#include <spdlog/spdlog.h>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <string>
#include <type_traits>
#include <variant>

namespace tsr::embree {

struct Renderer::Arena {
  explicit Arena(int threads) : arena(threads > 0 ? threads : tbb::task_arena::automatic) {}
  tbb::task_arena arena;
};

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Offset that escapes the surface's own float error at position p.
float rayEpsilon(const glm::vec3& p) {
  return 1e-4f * std::max(1.0f, std::max(std::abs(p.x), std::max(std::abs(p.y), std::abs(p.z))));
}

std::uint64_t settingsHash(const RenderSettings& s) {
  std::uint64_t h = splitmix64(s.seed);
  h = splitmix64(h ^ s.maxDepth);
  h = splitmix64(h ^ s.rouletteDepth);
  return splitmix64(h ^ std::uint64_t(s.lightSampling));
}

struct SurfaceHit {
  glm::vec3 p{0.0f};
  glm::vec3 faceNormal{0.0f};  // from the winding, world space
  glm::vec3 ng{0.0f};          // geometric normal on the side of ns
  glm::vec3 ns{0.0f};
  glm::vec2 uv{0.0f};  // texture coordinates where a texture is bound, else barycentrics
  const InstanceView* instance = nullptr;
  std::uint32_t prim = 0;
};

// Fills a ray with three 16-byte stores. Embree reads origin+tnear,
// direction+time and tfar+mask+id+flags as 16-byte vectors; filled field by
// field, each of those loads waits for four small stores to retire (no store
// forwarding), on every ray.
inline void setRay(RTCRay& ray, const glm::vec3& org, const glm::vec3& dir, float tfar) {
#if defined(__SSE2__)
  _mm_store_ps(&ray.org_x, _mm_setr_ps(org.x, org.y, org.z, 0.0f));
  _mm_store_ps(&ray.dir_x, _mm_setr_ps(dir.x, dir.y, dir.z, 0.0f));
  _mm_store_ps(&ray.tfar, _mm_castsi128_ps(_mm_setr_epi32(std::bit_cast<int>(tfar), -1, 0, 0)));
#else
  ray.org_x = org.x, ray.org_y = org.y, ray.org_z = org.z, ray.tnear = 0.0f;
  ray.dir_x = dir.x, ray.dir_y = dir.y, ray.dir_z = dir.z, ray.time = 0.0f;
  ray.tfar = tfar, ray.mask = ~0u, ray.id = 0, ray.flags = 0;
#endif
}

// Embree's own ray.valid(): origin and direction components within
// FLT_LARGE, a segment that is not NaN. Embree aborts on anything else, so
// such a ray is refused here (NaN fails every comparison).
inline bool traceable(const glm::vec3& org, const glm::vec3& dir, float tfar) {
  return std::abs(org.x) <= kMaxRayComponent && std::abs(org.y) <= kMaxRayComponent &&
         std::abs(org.z) <= kMaxRayComponent && std::abs(dir.x) <= kMaxRayComponent &&
         std::abs(dir.y) <= kMaxRayComponent && std::abs(dir.z) <= kMaxRayComponent && std::abs(tfar) <= kInf;
}

struct Tracer {
  const SceneState& scene;
  const RenderSettings& settings;
  std::uint64_t rays = 0;
  std::uint64_t refused = 0;  // rays Embree cannot trace: paths end there, shadow rays count as blocked

  bool intersect(const glm::vec3& org, const glm::vec3& dir, RTCRayHit& rh) {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    setRay(rh.ray, org, dir, kInf);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene.traversable, &ctx, &rh);
    ++rays;
    return rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
  }

  bool occluded(const glm::vec3& org, const glm::vec3& dir, float tfar) {
    if (!traceable(org, dir, tfar)) {
      ++refused;
      return true;
    }
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRay ray;
    setRay(ray, org, dir, tfar);
    rtcOccluded1(scene.traversable, &ctx, &ray);
    ++rays;
    return ray.tfar < 0.0f;
  }

  // What shading needs about a hit. Position and face normal come from the
  // ray and Embree's geometric normal; the mesh is read only for what it
  // adds: shading normals, and texture coordinates where a texture is bound.
  bool surface(const glm::vec3& org, const glm::vec3& dir, const RTCRayHit& rh, SurfaceHit& h) const {
    // A hit in the merged static scene names the instance by geometry id
    // (traced directly, or through its instance at top-level id 0).
    const std::uint32_t top = rh.hit.instID[0];
    const bool merged = top == RTC_INVALID_GEOMETRY_ID || top == kMergedTopId;
    const std::uint32_t inst = merged ? rh.hit.geomID : top - 1;
    if (inst >= scene.views.size() || !scene.views[inst].mesh) return false;
    const InstanceView& v = scene.views[inst];
    const MeshData& m = *v.mesh;
    h.instance = &v;
    h.prim = rh.hit.primID;
    h.p = org + rh.ray.tfar * dir;
    glm::vec3 n(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
    if (!merged) n = v.faceNormalTransform * n;  // instances report object-space normals
    const float len = glm::length(n);
    if (!(len > 0.0f) || !std::isfinite(len)) return false;
    h.faceNormal = n / len;
    h.ns = h.faceNormal;
    const float b1 = rh.hit.u, b2 = rh.hit.v, b0 = 1.0f - b1 - b2;
    h.uv = glm::vec2(b1, b2);
    const bool textured = (v.material->baseColorTexture || v.material->emissionTexture) && !m.uvs.empty();
    if (!m.normals.empty() || textured) {
      const std::uint32_t* idx = &m.indices[3 * std::size_t(h.prim)];
      if (!m.normals.empty()) {
        glm::vec3 ns = v.normalTransform * (b0 * m.normals[idx[0]] + b1 * m.normals[idx[1]] + b2 * m.normals[idx[2]]);
        float l = glm::length(ns);
        if (l > 0.0f && std::isfinite(l)) h.ns = ns / l;
      }
      if (textured) h.uv = b0 * m.uvs[idx[0]] + b1 * m.uvs[idx[1]] + b2 * m.uvs[idx[2]];
    }
    h.ng = glm::dot(h.faceNormal, h.ns) < 0.0f ? -h.faceNormal : h.faceNormal;
    return true;
  }

  static glm::vec3 baseColour(const ResolvedMaterial& m, const glm::vec2& uv) {
    glm::vec3 c = m.material.baseColor;
    if (m.baseColorTexture) c *= glm::vec3(m.baseColorTexture->sampleBilinear(uv));
    return c;
  }

  static glm::vec3 emission(const ResolvedMaterial& m, const glm::vec2& uv) {
    glm::vec3 e = m.material.emission;
    if (m.emissionTexture) e *= glm::vec3(m.emissionTexture->sampleBilinear(uv));
    return e;
  }

  // Solid-angle density with which emitter sampling would have produced
  // this hit, seen from distance t.
  float emitterPdf(const SurfaceHit& h, const glm::vec3& dir, float t) const {
    if (h.instance->emissiveOffset == kNotEmissive || scene.emitters.empty()) return 0.0f;
    float cosL = glm::dot(h.faceNormal, -dir);
    if (cosL <= 0.0f) return 0.0f;
    const std::uint32_t i = h.instance->emissiveOffset + h.prim;
    return scene.emitters.discreteProbability(i) / scene.emitterTriangles[i].area * t * t / cosL;
  }

  struct EmitterSample {
    glm::vec3 wi{0.0f};
    float dist = 0.0f;
    glm::vec3 radiance{0.0f};
    float pdf = 0.0f;
    glm::vec3 point{0.0f};
  };

  bool sampleEmitter(const glm::vec3& p, float uSelect, const glm::vec2& u, EmitterSample& out) const {
    float prob = 0.0f;
    std::uint32_t i = scene.emitters.sampleDiscrete(uSelect, &prob);
    auto it = std::upper_bound(scene.emissiveRanges.begin(), scene.emissiveRanges.end(), i,
                               [](std::uint32_t v, const EmissiveRange& r) { return v < r.offset; });
    const EmissiveRange& range = *(it - 1);
    const InstanceView& v = scene.views[range.instance];
    const EmitterTriangle& tri = scene.emitterTriangles[i];
    if (!(tri.area > 0.0f)) return false;
    glm::vec2 b = sampleTriangle(u);
    out.point = tri.p0 + b.x * tri.e1 + b.y * tri.e2;
    glm::vec3 d = out.point - p;
    float dist2 = glm::dot(d, d);
    if (!(dist2 > 0.0f)) return false;
    out.dist = std::sqrt(dist2);
    out.wi = d / out.dist;
    float cosL = glm::dot(tri.normal, -out.wi);
    if (cosL <= 0.0f) return false;
    const MeshData& m = *v.mesh;
    glm::vec2 uv = b;
    if (v.material->emissionTexture && !m.uvs.empty()) {
      const std::uint32_t* idx = &m.indices[3 * std::size_t(i - range.offset)];
      uv = (1.0f - b.x - b.y) * m.uvs[idx[0]] + b.x * m.uvs[idx[1]] + b.y * m.uvs[idx[2]];
    }
    out.radiance = emission(*v.material, uv);
    out.pdf = prob / tri.area * dist2 / cosL;
    return out.pdf > 0.0f && std::isfinite(out.pdf);
  }

  PixelSample tracePath(Rng& rng, glm::vec3 org, glm::vec3 dir, const glm::vec3& camPos, const glm::vec3& forward);
};

PixelSample Tracer::tracePath(Rng& rng, glm::vec3 org, glm::vec3 dir, const glm::vec3& camPos,
                              const glm::vec3& forward) {
  PixelSample out;
  const Environment& env = scene.environment;
  const bool envActive = !env.isBlack();
  const LightSampling mode = settings.lightSampling;
  auto add = [&out](const glm::vec3& c, std::uint32_t scatterEvents) {
    if (!finite(c)) return;  // a NaN sample would poison the running mean forever
    (scatterEvents <= 1 ? out.direct : out.indirect) += c;
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
        add(throughput * env.radiance(dir) * w, depth);
      }
      break;
    }
    SurfaceHit h;
    if (!surface(org, dir, rh, h)) break;
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
      add(throughput * emission(mat, h.uv) * w, depth);
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
    glm::vec3 nextThroughput = throughput;
    if (continues) {
      nextThroughput *= bs.weight;
      if (depth + 1 >= settings.rouletteDepth) {
        float q = std::min(maxComponent(nextThroughput), 0.95f);
        if (!(q > 0.0f) || rng.uniform() >= q) continues = false;
        else nextThroughput /= q;
      }
    }
    const glm::vec3 nextOrg = spawn(nextDir);

    if (nextEvent) {
      for (const Light& light : scene.activeLights) {
        glm::vec3 wi, li;
        float tfar = kInf;
        if (const auto* pl = std::get_if<PointLight>(&light)) {
          glm::vec3 d = pl->position - h.p;
          float d2 = glm::dot(d, d);
          if (!(d2 > 0.0f)) continue;
          float dist = std::sqrt(d2);
          wi = d / dist;
          li = pl->intensity / d2;
          tfar = dist * (1.0f - 1e-4f);
        } else if (const auto* sl = std::get_if<SpotLight>(&light)) {
          glm::vec3 d = sl->position - h.p;
          float d2 = glm::dot(d, d);
          if (!(d2 > 0.0f)) continue;
          float dist = std::sqrt(d2);
          wi = d / dist;
          float c = glm::dot(glm::normalize(sl->direction), -wi);
          float cosOuter = std::cos(sl->outerAngle), cosInner = std::cos(sl->innerAngle);
          float falloff = c >= cosInner ? 1.0f
                          : c <= cosOuter ? 0.0f
                                          : glm::smoothstep(cosOuter, cosInner, c);
          if (falloff <= 0.0f) continue;
          li = sl->intensity * (falloff / d2);
          tfar = dist * (1.0f - 1e-4f);
        } else {
          const auto& dl = std::get<DirectionalLight>(light);
          wi = -glm::normalize(dl.direction);
          li = dl.irradiance;
        }
        glm::vec3 f = evalWorld(wi, nullptr);  // delta lights: no MIS
        if (maxComponent(f) <= 0.0f) continue;
        if (!occluded(spawn(wi), wi, tfar)) add(throughput * f * li, depth + 1);
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
              add(throughput * f * es.radiance * (lightSampleWeight(es.pdf, bsdfPdf) / es.pdf), depth + 1);
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
            add(throughput * f * es.radiance * (lightSampleWeight(es.pdf, bsdfPdf) / es.pdf), depth + 1);
          }
        }
      }
    }

    if (!continues) break;
    throughput = nextThroughput;
    prevPdf = bs.pdf;
    prevDelta = bs.delta;
    org = nextOrg;
    dir = nextDir;
  }
  return out;
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

PassResult Renderer::renderPass(Scene& scene, const Camera& camera, const Region& region, FrameBuffer& fb) {
  camera.validate();
  region.validate();
  if (fb.width() != region.regionWidth() || fb.height() != region.regionHeight()) {
    throw Error("frame buffer is " + std::to_string(fb.width()) + "x" + std::to_string(fb.height()) +
                " but the region is " + std::to_string(region.regionWidth()) + "x" +
                std::to_string(region.regionHeight()));
  }
  scene.commit();

  PassResult result;
  FrameBuffer::Key key{scene.uid(), scene.version(), camera, region, settingsHash(settings_)};
  if (!fb.key_ || !(*fb.key_ == key)) {
    fb.reset();
    fb.key_ = key;
    result.restarted = true;
  }

  const SceneState& state = scene.state();
  const RenderSettings settings = settings_;
  const std::uint32_t ts = settings.tileSize;
  const std::uint32_t rw = region.regionWidth(), rh = region.regionHeight();
  const std::uint32_t tilesX = (rw + ts - 1) / ts, tilesY = (rh + ts - 1) / ts;
  std::vector<std::uint64_t> tileRays(std::size_t(tilesX) * tilesY, 0);
  std::vector<std::uint64_t> tileRefused(tileRays.size(), 0);
  const glm::vec3 camPos(camera.cameraToWorld[3]);
  const glm::vec3 forward = glm::normalize(-glm::vec3(camera.cameraToWorld[2]));
  const glm::mat3 camRot(camera.cameraToWorld);
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
      std::uint32_t py = region.y0 + y;
      for (std::uint32_t x = xb; x < xe; ++x) {
        std::uint32_t px = region.x0 + x;
        const std::uint64_t pixelKey = Rng::pixelKey(settings.seed, px, py);
        const std::uint32_t firstSample = fb.sampleCount(x, y);
        for (std::uint32_t s = 0; s < settings.samplesPerPass; ++s) {
          Rng rng(pixelKey, firstSample + s);
          glm::vec2 j = rng.uniform2();
          float cx = camera.left + (camera.right - camera.left) * ((float(px) + j.x) / float(region.width));
          float cy = camera.top - (camera.top - camera.bottom) * ((float(py) + j.y) / float(region.height));
          glm::vec3 dir = glm::normalize(camRot * glm::vec3(cx, cy, -camera.near));
          fb.accumulate(x, y, tracer.tracePath(rng, camPos, dir, camPos, forward));
        }
      }
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

}  // namespace tsr::embree
