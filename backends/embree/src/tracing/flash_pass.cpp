#include "tracing/tracer.hpp"

namespace tsr::embree {

namespace {

// Share of ambient light in the flash image; the head light gives the rest
// through its cosine, so surfaces facing the eye reach their reflectivity.
constexpr float kAmbient = 0.25f;
// On glossy surfaces the head light's share is smaller: what they show is
// a blurred reflection, not a cosine falloff, and a steep falloff would
// cut a sphere into rings of equal cosine that the filter averages along.
// The normal's share that is left still tells a cube's faces apart.
constexpr float kGlossyAmbient = 0.75f;
// Glossy surfaces smoother than this GGX alpha (roughness 0.2) show, in
// part, what they reflect: their reflection is sharp at the scale of a
// few pixels, and without its edges in the range buffer the filter washes
// it out. The share falls linearly to 0 at this alpha, so a rougher
// surface, whose reflection is as blurred as the filter's kernel, shows
// only itself: followed, its reflection would look sharper filtered than
// its roughness makes it.
constexpr float kSharpGlossyAlpha = 0.04f;
// Specular bounces followed per camera ray; glass splits into reflection
// and refraction, so the ray tree is capped by a stack of pending rays.
constexpr std::uint32_t kMaxSpecularDepth = 8;
constexpr int kStack = 16;
// Emitters look like their own colour in the flash image (clamped to the
// flash's range), so a lamp and the ceiling around it are told apart.
constexpr float kEmissionShare = 0.5f;

struct FlashRay {
  glm::vec3 org;
  glm::vec3 dir;
  glm::vec3 weight;
  std::uint32_t depth;
};

}  // namespace

glm::vec3 Tracer::traceFlash(glm::vec3 org, glm::vec3 dir, const glm::vec3& eye, float& distance) {
  distance = kInf;
  FlashRay stack[kStack];
  int top = 0;
  stack[top++] = {org, dir, glm::vec3(1.0f), 0};
  glm::vec3 result(0.0f);
  while (top > 0) {
    const FlashRay r = stack[--top];
    RTCRayHit rh;
    if (!intersect(r.org, r.dir, rh)) {
      // The background seen directly is a class of its own; seen in a
      // mirror it is black.
      if (r.depth == 0) result = kFlashMiss;
      continue;
    }
    SurfaceHit h;
    if (!surface(r.org, r.dir, rh, h)) continue;
    if (r.depth == 0) distance = rh.ray.tfar;
    const ResolvedMaterial& mat = *h.instance->material;
    const SurfaceParameters at = parameters(mat, h.uv);
    const glm::vec3& base = at.colour;
    const bool front = glm::dot(r.dir, h.ng) < 0.0f;
    const glm::vec3 n = front ? h.ns : -h.ns;
    const MaterialType type = closestClass(mat.material.type, at.roughness, at.metallic, at.transmission);
    // Perfect specular surfaces are followed (3.3.3), near-perfect glossy
    // ones in part (kSharpGlossyAlpha).
    const bool specular = type == MaterialType::Mirror || type == MaterialType::Glass;
    const float alpha = at.roughness * at.roughness;
    const bool glossy = type == MaterialType::Conductor || type == MaterialType::Dielectric;
    const float eps = rayEpsilon(h.p);
    const glm::vec3 ng = front ? h.ng : -h.ng;
    if (!specular || r.depth >= kMaxSpecularDepth) {
      const glm::vec3 toEye = glm::normalize(eye - h.p);
      const float head = std::max(0.0f, glm::dot(n, toEye));
      const float ambient = type == MaterialType::Diffuse ? kAmbient : kGlossyAmbient;
      glm::vec3 c = base * (ambient + (1.0f - ambient) * head);
      if (mat.material.isEmissive()) c += kEmissionShare * glm::min(emission(mat, h.uv), glm::vec3(1.0f));
      const float mirrored = glossy && r.depth < kMaxSpecularDepth && top < kStack
                                 ? std::max(0.0f, 1.0f - alpha / kSharpGlossyAlpha)
                                 : 0.0f;
      result += r.weight * (1.0f - mirrored) * c;
      if (mirrored > 0.0f)
        stack[top++] = {h.p + ng * eps, glm::reflect(r.dir, n), r.weight * mirrored * base, r.depth + 1};
      continue;
    }
    const glm::vec3 reflected = glm::reflect(r.dir, n);
    glm::vec3 reflectWeight = r.weight * base;
    glm::vec3 refractWeight(0.0f);
    glm::vec3 refracted(0.0f);
    if (type == MaterialType::Glass) {
      const float eta = front ? mat.material.ior : 1.0f / mat.material.ior;
      const float f = fresnelDielectric(glm::dot(-r.dir, n), eta);
      refracted = glm::refract(r.dir, n, 1.0f / eta);
      if (f < 1.0f && glm::dot(refracted, refracted) > 0.0f) {
        refractWeight = r.weight * base * (1.0f - f);
        reflectWeight = r.weight * f;
      } else {
        reflectWeight = r.weight;  // total internal reflection
      }
    }
    // With a full stack only the stronger branch goes on, carrying both
    // weights so that the flash keeps its brightness.
    const bool both = maxComponent(refractWeight) > 0.0f;
    if (both && top + 2 > kStack) {
      if (maxComponent(refractWeight) > maxComponent(reflectWeight)) {
        stack[top++] = {h.p - ng * eps, glm::normalize(refracted), refractWeight + reflectWeight, r.depth + 1};
      } else {
        stack[top++] = {h.p + ng * eps, reflected, refractWeight + reflectWeight, r.depth + 1};
      }
      continue;
    }
    if (top < kStack) stack[top++] = {h.p + ng * eps, reflected, reflectWeight, r.depth + 1};
    if (both && top < kStack) stack[top++] = {h.p - ng * eps, glm::normalize(refracted), refractWeight, r.depth + 1};
  }
  return result;
}

}  // namespace tsr::embree
