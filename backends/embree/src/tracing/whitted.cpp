// Tracer::traceWhitted: the middle renderer of Schwenk's figure 5.6, shown
// as soon as the camera rests and before the path tracer has converged. A
// Whitted-style ray tree (Whitted 1980): every delta lobe (mirrors, glass,
// smooth metallic-roughness surfaces) is followed whole, so reflections and
// refractions are sharp; every other surface is lit straight from the
// lights, each behind one shadow ray, so shadows are hard. Area lights
// shine from the centroids of their triangles (all of them up to
// kLightPoints, else kLightPoints of them stratified by power); the
// environment lights a surface from its normal's direction, unshadowed.
// No indirect light, no random numbers: one sample per pixel is the image.
#include "tracing/delta_lights.hpp"
#include "tracing/scattering_point.hpp"
#include "tracing/tracer.hpp"

namespace tsr::embree {

namespace {

// Branches followed per camera ray: glass splits each ray in two, so the
// tree is held by a stack of pending rays.
constexpr int kStack = 16;
// Emitter triangles lit from one point each; more are stratified.
constexpr std::uint32_t kLightPoints = 16;
// Branches carrying less than this share of the camera ray are dropped.
constexpr float kMinWeight = 1e-3f;

struct Branch {
  glm::vec3 org;
  glm::vec3 dir;
  glm::vec3 weight;
  std::uint32_t depth;
};

}  // namespace

PixelSample Tracer::traceWhitted(const glm::vec3& org, const glm::vec3& dir, const glm::vec3& camPos,
                                 const glm::vec3& forward) {
  PixelSample out;
  const Environment& env = scene.environment;
  const bool envActive = !env.isBlack();
  const std::uint32_t triangles = std::uint32_t(scene.emitterTriangles.size());
  const bool allTriangles = triangles <= kLightPoints;
  const std::uint32_t lightPoints = scene.emitters.empty() ? 0 : allTriangles ? triangles : kLightPoints;
  // Barycentrics of a triangle's centroid.
  const glm::vec2 centroid(1.0f / 3.0f);

  auto shadowed = [&](const glm::vec3& o, const glm::vec3& d, float tfar) { return occluded(o, d, tfar); };
  // Light reaching a non-specular point straight from the lights.
  auto direct = [&](const ScatteringPoint& sp) {
    glm::vec3 sum(0.0f);
    for (const Light& light : scene.activeLights) {
      LightArrival a;
      if (!lightArriving(light, sp.p, a)) continue;
      const glm::vec3 f = sp.eval(a.wi, nullptr);
      if (maxComponent(f) <= 0.0f || shadowed(sp.spawn(a.wi), a.wi, a.tfar)) continue;
      sum += f * a.li;
    }
    for (std::uint32_t k = 0; k < lightPoints; ++k) {
      float prob = 1.0f;
      std::uint32_t i = k;
      if (!allTriangles) {
        i = scene.emitters.sampleDiscrete((float(k) + 0.5f) / float(lightPoints), &prob);
        prob *= float(lightPoints);
      }
      EmitterSample es;
      if (!emitterPoint(sp.p, i, prob, centroid, es)) continue;
      const glm::vec3 f = sp.eval(es.wi, nullptr);
      if (maxComponent(f) <= 0.0f) continue;
      const ShadowRay ray = shadowRayTo(sp, es.point, es.wi);
      if (shadowed(ray.org, ray.dir, ray.tfar)) continue;
      sum += f * es.radiance / es.pdf;
    }
    if (envActive) sum += sp.bsdf.colour * env.radiance(sp.frame.n);
    return sum;
  };
  auto add = [&](const glm::vec3& c) {
    if (finite(c)) out.direct += c;
  };

  Branch stack[kStack];
  int top = 0;
  stack[top++] = {org, dir, glm::vec3(1.0f), 0};
  bool first = true;
  while (top > 0) {
    const Branch r = stack[--top];
    const bool camera = first;
    first = false;
    RTCRayHit rh;
    if (!intersect(r.org, r.dir, rh)) {
      if (envActive) add(r.weight * env.radiance(r.dir));
      continue;
    }
    SurfaceHit h;
    if (!surface(r.org, r.dir, rh, h)) continue;
    const ResolvedMaterial& mat = *h.instance->material;
    const SurfaceParameters at = parameters(mat, h.uv);
    if (camera) {
      out.hit = true;
      out.depth = glm::dot(h.p - camPos, forward);
      out.albedo = at.colour;
      out.normal = glm::dot(h.ns, r.dir) > 0.0f ? -h.ns : h.ns;
    }
    if (mat.material.isEmissive() && glm::dot(h.faceNormal, r.dir) < 0.0f) add(r.weight * emission(mat, h.uv));
    const ScatteringPoint sp(h, r.dir, mat.material, at);
    if (sp.facesAway()) continue;
    if (!sp.bsdf.isDelta()) add(r.weight * direct(sp));
    if (r.depth >= settings.maxDepth) continue;
    SpecularLobe lobes[2];
    const int n = sp.bsdf.specularLobes(sp.woL, lobes);
    for (int k = 0; k < n && top < kStack; ++k) {
      const glm::vec3 weight = r.weight * lobes[k].weight;
      if (!(maxComponent(weight) > kMinWeight)) continue;
      const glm::vec3 wi = glm::normalize(sp.frame.toWorld(lobes[k].wi));
      if ((glm::dot(wi, sp.ng) > 0.0f) != (lobes[k].wi.z > 0.0f)) continue;  // shading and geometry disagree
      stack[top++] = {sp.spawn(wi), wi, weight, r.depth + 1};
    }
  }
  return out;
}

}  // namespace tsr::embree
