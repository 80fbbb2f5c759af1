#pragma once
// A surface hit made ready to scatter light: the side the ray came from,
// the shading frame turned to that side, the material's BSDF there, and
// where rays leaving it start. Paths and photons scatter alike through it.
// Private to the back-end.
#include "tracing/bsdf.hpp"
#include "tracing/tracer.hpp"

#include <glm/geometric.hpp>

#include <algorithm>

namespace tsr::embree {

struct ScatteringPoint {
  glm::vec3 p;
  glm::vec3 wo;  // towards where the ray came from
  bool front;    // wo is on the side of the geometric normal
  glm::vec3 ng;  // geometric normal on the side of wo
  Frame frame;   // shading frame, its normal on the side of wo
  glm::vec3 woL;
  float eps;
  Bsdf bsdf;

  // `at` is the material's parameters at the hit (textured or not).
  ScatteringPoint(const SurfaceHit& h, const glm::vec3& dir, const Material& m, const SurfaceParameters& at)
      : p(h.p),
        wo(-dir),
        front(glm::dot(wo, h.ng) > 0.0f),
        ng(front ? h.ng : -h.ng),
        frame(front ? h.ns : -h.ns),
        woL(frame.toLocal(wo)),
        eps(rayEpsilon(h.p)) {
    bsdf.type = m.type;
    bsdf.colour = at.colour;
    bsdf.alpha = std::max(1e-3f, at.roughness * at.roughness);
    if (m.type == MaterialType::MetallicRoughness && at.roughness < kSmoothRoughness) bsdf.alpha = 0.0f;
    bsdf.eta = front ? m.ior : 1.0f / m.ior;
    bsdf.metallic = at.metallic;
    bsdf.specular = m.specular;
    bsdf.transmission = at.transmission;
    if (!facesAway()) bsdf.prepare(woL);
  }

  // The shading normal faces away from the viewer: no consistent answer.
  bool facesAway() const { return woL.z <= 1e-6f; }

  // Where a ray leaving towards w starts: off the surface on w's side.
  glm::vec3 spawn(const glm::vec3& w) const { return p + ng * (glm::dot(w, ng) > 0.0f ? eps : -eps); }

  // f * |cos| for a world direction, zero when shading and geometry
  // disagree; and the BSDF's sampling density where MIS needs it.
  glm::vec3 eval(const glm::vec3& wi, float* pdf) const {
    glm::vec3 wiL = frame.toLocal(wi);
    if ((glm::dot(wi, ng) > 0.0f) != (wiL.z > 0.0f)) {
      if (pdf) *pdf = 0.0f;
      return glm::vec3(0.0f);
    }
    return bsdf.evalPdf(woL, wiL, pdf);
  }

  // A direction sampled from the BSDF, in world space as `wi`; false when
  // the BSDF gives none or it leaves on the other side of the geometry
  // than of the shading normal.
  bool sample(const glm::vec2& u, float uLobe, BsdfSample& bs, glm::vec3& wi) const {
    if (!bsdf.sample(woL, u, uLobe, bs)) return false;
    wi = glm::normalize(frame.toWorld(bs.wi));
    return (glm::dot(wi, ng) > 0.0f) == (bs.wi.z > 0.0f);
  }
};

// A shadow ray from `from` (a scattering point, or a point in a medium)
// to `target`, a point on a light that wi points at: it leaves where
// from.spawn(wi) says and aims from there, so it meets the light's surface
// at the target itself and stops just short of it. (Aimed along wi from the
// offset origin instead, it crosses the light's plane early at oblique
// angles and finds the light itself in the way.)
struct ShadowRay {
  glm::vec3 org, dir;
  float tfar;
};
template <class Point>
ShadowRay shadowRayTo(const Point& from, const glm::vec3& target, const glm::vec3& wi) {
  const glm::vec3 o = from.spawn(wi), d = target - o;
  const float dist = glm::length(d);
  return {o, d / dist, dist - rayEpsilon(target)};
}

}  // namespace tsr::embree
