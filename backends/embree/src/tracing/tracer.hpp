#pragma once
// The ray-casting core shared by the renderer's passes: rays filled for
// Embree, hit records turned into surface points, emitter sampling. The
// path tracer (path_tracer.cpp), the range-buffer pass (flash_pass.cpp)
// and the photon pass (photons/photon_pass.cpp) build on it. Private to
// the back-end.
#include "limits.hpp"
#include "scene/scene_state.hpp"
#include "tracing/alpha_test.hpp"
#include "tracing/bsdf.hpp"
#include "tsr/embree/framebuffer.hpp"
#include "tsr/embree/irradiance_field.hpp"
#include "tsr/embree/radiance_filter.hpp"
#include "tsr/embree/renderer.hpp"
#include "tsr/embree/rng.hpp"
#include "tsr/embree/sampler.hpp"
#include "tsr/embree/sampling.hpp"

#include <glm/geometric.hpp>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <type_traits>

namespace tsr::embree {

inline constexpr float kInf = std::numeric_limits<float>::infinity();

inline bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Offset that escapes the surface's own float error at position p.
inline float rayEpsilon(const glm::vec3& p) {
  return 1e-4f * std::max(1.0f, std::max(std::abs(p.x), std::max(std::abs(p.y), std::abs(p.z))));
}

// A material's parameters at one hit, its textures applied.
struct SurfaceParameters {
  glm::vec3 colour{0.0f};
  float roughness = 0.5f;
  float metallic = 0.0f;
  float transmission = 0.0f;
};

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
inline void setRay(RTCRay& ray, const glm::vec3& org, const glm::vec3& dir, float tfar, float time) {
#if defined(__SSE2__)
  _mm_store_ps(&ray.org_x, _mm_setr_ps(org.x, org.y, org.z, 0.0f));
  _mm_store_ps(&ray.dir_x, _mm_setr_ps(dir.x, dir.y, dir.z, time));
  _mm_store_ps(&ray.tfar, _mm_castsi128_ps(_mm_setr_epi32(std::bit_cast<int>(tfar), -1, 0, 0)));
#else
  ray.org_x = org.x, ray.org_y = org.y, ray.org_z = org.z, ray.tnear = 0.0f;
  ray.dir_x = dir.x, ray.dir_y = dir.y, ray.dir_z = dir.z, ray.time = time;
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

// The intersection context of the top and the moving level. While the top
// level holds ghosts (instances that moved to the moving level,
// SceneState::ghosts), hits on them are rejected, so a ray sees what lies
// behind; while some material is alpha-tested, hits its alpha cuts away or
// lets pass are rejected (alpha_test.hpp). Otherwise there is no filter
// and no cost.
struct TopLevelContext {
  RTCIntersectContext context;  // first: Embree hands the filter a pointer to it
  const SceneState* scene;
  const std::vector<std::uint32_t>* movingIds = nullptr;  // set for the moving level: its ids to instances

  explicit TopLevelContext(const SceneState& s, bool movingLevel = false) : scene(&s) {
    rtcInitIntersectContext(&context);
    if (movingLevel) movingIds = &s.movingIds;
    if ((!movingLevel && s.ghostCount > 0) || s.alphaTested) [[unlikely]]
      context.filter = filterHits;
  }

  static void filterHits(const RTCFilterFunctionNArguments* args) {
    const auto& self = *reinterpret_cast<const TopLevelContext*>(args->context);
    const SceneState& s = *self.scene;
    const unsigned n = args->N;
    for (unsigned i = 0; i < n; ++i) {
      if (args->valid[i] == 0) continue;
      const unsigned top = RTCHitN_instID(args->hit, n, i, 0);
      if (!self.movingIds && top < s.ghosts.size() && s.ghosts[top]) {
        args->valid[i] = 0;
        continue;
      }
      if (!s.alphaTested) continue;
      std::uint32_t inst;
      if (self.movingIds)
        inst = top < self.movingIds->size() ? (*self.movingIds)[top] : kNoId;
      else
        inst = (top == RTC_INVALID_GEOMETRY_ID || top == kMergedTopId) ? RTCHitN_geomID(args->hit, n, i) : top - 1;
      if (alphaRejects(s, inst, args, i)) args->valid[i] = 0;
    }
  }
};
static_assert(std::is_standard_layout_v<TopLevelContext>);

struct Tracer {
  const SceneState& scene;
  const RenderSettings& settings;
  std::uint64_t rays = 0;
  std::uint64_t refused = 0;  // rays Embree cannot trace: paths end there, shadow rays count as blocked
  // With a field, a path ends at its first Diffuse vertex after direct
  // lighting there (emitters by light sampling alone), and the indirect
  // light there is albedo / pi x the field's irradiance.
  const IrradianceField* irradiance = nullptr;
  // The time in the frame interval every ray of the current path is traced
  // at (0: its start, 1: its end), where moving instances stand.
  float time = 0.0f;

  // An untraceable ray is refused and counts as a miss; the path tracer
  // checks first and ends the path instead.
  bool intersect(const glm::vec3& org, const glm::vec3& dir, RTCRayHit& rh, float tfar = kInf) {
    if (!traceable(org, dir, tfar)) {
      ++refused;
      return false;
    }
    TopLevelContext top(scene);
    setRay(rh.ray, org, dir, tfar, time);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene.traversable, &top.context, &rh);
    if (scene.movingTraversable) [[unlikely]]
      intersectMoving(rh);
    ++rays;
    return rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
  }

  // The moving level, traced up to the nearest hit so far: a hit there is
  // nearer and is renamed to the instance's top-level id.
  [[gnu::noinline]] void intersectMoving(RTCRayHit& rh) const {
    TopLevelContext moving(scene, true);
    const RTCHit nearest = rh.hit;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene.movingTraversable, &moving.context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID)
      rh.hit = nearest;
    else
      rh.hit.instID[0] = topId(scene.movingIds[rh.hit.instID[0]]);
  }

  bool occluded(const glm::vec3& org, const glm::vec3& dir, float tfar) {
    if (!traceable(org, dir, tfar)) {
      ++refused;
      return true;
    }
    TopLevelContext top(scene);
    RTCRay ray;
    setRay(ray, org, dir, tfar, time);
    rtcOccluded1(scene.traversable, &top.context, &ray);
    if (scene.movingTraversable && ray.tfar >= 0.0f) [[unlikely]] {
      TopLevelContext moving(scene, true);
      rtcOccluded1(scene.movingTraversable, &moving.context, &ray);
    }
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
    // A moving instance stands where the ray's time puts it.
    glm::mat3 moved(1.0f), movedNormal(1.0f);
    const glm::mat3* normalTransform = &v.normalTransform;
    if (v.motion) [[unlikely]] {
      moved = glm::mat3(v.motion->at(time));
      movedNormal = glm::transpose(glm::inverse(moved));
      normalTransform = &movedNormal;
    }
    if (!merged)  // instances report object-space normals
      n = v.motion ? glm::determinant(moved) * movedNormal * n : v.faceNormalTransform * n;
    const float len = glm::length(n);
    if (!(len > 0.0f) || !std::isfinite(len)) return false;
    h.faceNormal = n / len;
    h.ns = h.faceNormal;
    const float b1 = rh.hit.u, b2 = rh.hit.v, b0 = 1.0f - b1 - b2;
    h.uv = glm::vec2(b1, b2);
    const ResolvedMaterial& r = *v.material;
    const bool textured = (r.baseColorTexture || r.emissionTexture || r.metallicRoughnessTexture ||
                           r.transmissionTexture || r.normalTexture) &&
                          !m.uvs.empty();
    if (!m.normals.empty() || textured) {
      const std::uint32_t* idx = &m.indices[3 * std::size_t(h.prim)];
      if (!m.normals.empty()) {
        glm::vec3 ns = *normalTransform * (b0 * m.normals[idx[0]] + b1 * m.normals[idx[1]] + b2 * m.normals[idx[2]]);
        float l = glm::length(ns);
        if (l > 0.0f && std::isfinite(l)) h.ns = ns / l;
      }
      if (textured) h.uv = b0 * m.uvs[idx[0]] + b1 * m.uvs[idx[1]] + b2 * m.uvs[idx[2]];
      if (textured && r.normalTexture) applyNormalMap(v, v.motion ? moved : glm::mat3(v.transform), idx, h);
    }
    h.ng = glm::dot(h.faceNormal, h.ns) < 0.0f ? -h.faceNormal : h.faceNormal;
    return true;
  }

  // The tangent-space normal map at h.uv turns h.ns. Tangents come from the
  // triangle's uv derivatives (meshes carry none), bitangents from the
  // normal and the uv orientation, as glTF's MikkTSpace-less fallback.
  static void applyNormalMap(const InstanceView& v, const glm::mat3& linear, const std::uint32_t* idx, SurfaceHit& h) {
    const MeshData& m = *v.mesh;
    const glm::vec3 e1 = linear * (m.positions[idx[1]] - m.positions[idx[0]]);
    const glm::vec3 e2 = linear * (m.positions[idx[2]] - m.positions[idx[0]]);
    // Derivatives in the normal map's (transformed) texture space.
    const UvTransform& uv = v.material->material.normalUv;
    const glm::vec2 d1 = uv(m.uvs[idx[1]]) - uv(m.uvs[idx[0]]), d2 = uv(m.uvs[idx[2]]) - uv(m.uvs[idx[0]]);
    const float det = d1.x * d2.y - d2.x * d1.y;
    if (!(std::abs(det) > 1e-12f)) return;
    glm::vec3 t = (e1 * d2.y - e2 * d1.y) / det;
    const glm::vec3 b = (e2 * d1.x - e1 * d2.x) / det;
    t -= h.ns * glm::dot(h.ns, t);
    const float tl = glm::length(t);
    if (!(tl > 0.0f) || !std::isfinite(tl)) return;
    t /= tl;
    const glm::vec3 bitangent = glm::cross(h.ns, t) * (glm::dot(glm::cross(h.ns, t), b) < 0.0f ? -1.0f : 1.0f);
    const glm::vec3 c = 2.0f * glm::vec3(v.material->normalTexture->sampleBilinear(uv(h.uv))) - 1.0f;
    const float k = v.material->material.normalScale;
    const glm::vec3 n = (k * c.x) * t + (k * c.y) * bitangent + c.z * h.ns;
    const float l = glm::length(n);
    if (l > 0.0f && std::isfinite(l)) h.ns = n / l;
  }

  static SurfaceParameters parameters(const ResolvedMaterial& m, const glm::vec2& uv) {
    SurfaceParameters p;
    p.colour = baseColour(m, uv);
    p.roughness = m.material.roughness;
    p.metallic = m.material.metallic;
    p.transmission = m.material.transmission;
    if (m.metallicRoughnessTexture) {
      const glm::vec4 t = m.metallicRoughnessTexture->sampleBilinear(m.material.metallicRoughnessUv(uv));
      p.roughness = std::clamp(p.roughness * t.y, 0.0f, 1.0f);
      p.metallic = std::clamp(p.metallic * t.z, 0.0f, 1.0f);
    }
    if (m.transmissionTexture)
      p.transmission = std::clamp(
          p.transmission * m.transmissionTexture->sampleBilinear(m.material.transmissionUv(uv)).x, 0.0f, 1.0f);
    return p;
  }

  static glm::vec3 baseColour(const ResolvedMaterial& m, const glm::vec2& uv) {
    glm::vec3 c = m.material.baseColor;
    if (m.baseColorTexture) c *= glm::vec3(m.baseColorTexture->sampleBilinear(m.material.baseColorUv(uv)));
    return c;
  }

  static glm::vec3 emission(const ResolvedMaterial& m, const glm::vec2& uv) {
    glm::vec3 e = m.material.emission;
    if (m.emissionTexture) e *= glm::vec3(m.emissionTexture->sampleBilinear(m.material.emissionUv(uv)));
    return e;
  }

  bool byTree() const { return settings.lightChoice == LightChoice::Tree; }

  // Solid-angle density with which emitter sampling at `from` (normal n,
  // zero in a medium) would have produced this hit, seen from distance t.
  float emitterPdf(const SurfaceHit& h, const glm::vec3& dir, float t, const glm::vec3& from,
                   const glm::vec3& n) const {
    if (h.instance->emissiveOffset == kNotEmissive || scene.emitters.empty()) return 0.0f;
    float cosL = glm::dot(h.faceNormal, -dir);
    if (cosL <= 0.0f) return 0.0f;
    return emitterSolidAnglePdf(from, n, h.instance->emissiveOffset + h.prim, t, cosL);
  }

  // The density, in solid angle at a point `dist` away, with which light
  // sampling at `from` (normal n) picks a point of emitter triangle i seen
  // at cosine cosL from its side.
  float emitterSolidAnglePdf(const glm::vec3& from, const glm::vec3& n, std::uint32_t i, float dist, float cosL) const {
    return emitterProbability(from, n, i) / scene.emitterTriangles[i].area * dist * dist / cosL;
  }

  // The probability with which pickEmitter(from, n, ...) picks triangle i.
  float emitterProbability(const glm::vec3& from, const glm::vec3& n, std::uint32_t i) const {
    return byTree() ? scene.emitterTree.pmf(from, n, i) : scene.emitters.discreteProbability(i);
  }

  struct EmitterSample {
    glm::vec3 wi{0.0f};
    float dist = 0.0f;
    glm::vec3 radiance{0.0f};
    float pdf = 0.0f;
    glm::vec3 point{0.0f};
    std::uint32_t triangle = 0;
  };

  // The emitter triangle light sampling picks for point p with normal n
  // (zero in a medium), and its probability.
  bool pickEmitter(const glm::vec3& p, const glm::vec3& n, float uSelect, std::uint32_t& i, float& prob) const {
    if (byTree()) return scene.emitterTree.sample(p, n, uSelect, i, prob);
    i = scene.emitters.sampleDiscrete(uSelect, &prob);
    return prob > 0.0f;
  }

  // A point on an emitter triangle for shading point p with normal n
  // (zero in a medium).
  bool sampleEmitter(const glm::vec3& p, const glm::vec3& n, float uSelect, const glm::vec2& u,
                     EmitterSample& out) const {
    float prob = 0.0f;
    std::uint32_t i = 0;
    return pickEmitter(p, n, uSelect, i, prob) && emitterPoint(p, i, prob, sampleTriangle(u), out);
  }

  // The point with barycentrics b on emitter triangle i, picked with
  // probability prob, as light arriving at p.
  bool emitterPoint(const glm::vec3& p, std::uint32_t i, float prob, const glm::vec2& b, EmitterSample& out) const {
    auto it = std::upper_bound(scene.emissiveRanges.begin(), scene.emissiveRanges.end(), i,
                               [](std::uint32_t v, const EmissiveRange& r) { return v < r.offset; });
    const EmissiveRange& range = *(it - 1);
    const InstanceView& v = scene.views[range.instance];
    const EmitterTriangle& tri = scene.emitterTriangles[i];
    if (!(tri.area > 0.0f)) return false;
    out.triangle = i;
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

  // One path. With a record (zero-initialised by the caller), also fills
  // the radiance sample at the first non-specular vertex: Ľ_i collects
  // exactly the contributions classified indirect.
  PixelSample tracePath(Sampler& sampler, glm::vec3 org, glm::vec3 dir, const glm::vec3& camPos,
                        const glm::vec3& forward, RadianceSample* record = nullptr);
  // The "virtual flash" colour of one camera ray (Schwenk 3.3.3): the
  // reflectivity of the first non-specular surface, perfect specular
  // surfaces followed Whitted-style, lit by ambient light plus an
  // unoccluded head light at the eye.
  // `distance` receives the camera ray's hit distance (+inf on a miss).
  glm::vec3 traceFlash(glm::vec3 org, glm::vec3 dir, const glm::vec3& eye, float& distance);
  // One Whitted-style sample of a camera ray (whitted.cpp): perfect
  // specular lobes followed as a ray tree, every other surface lit directly
  // with hard shadows; no random numbers.
  PixelSample traceWhitted(const glm::vec3& org, const glm::vec3& dir, const glm::vec3& camPos,
                           const glm::vec3& forward);
};

}  // namespace tsr::embree
