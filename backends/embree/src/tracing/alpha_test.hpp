#pragma once
// Alpha-tested surfaces (AlphaMode): whether a ray passes a candidate hit,
// decided in the tracer's context filter so that camera rays and shadow
// rays see the same cut-outs. Blend decides by a number fixed by the ray
// and the triangle, so a render is the same on any thread, tile or node.
#include <bit>
#include <cstdint>

#include "scene/scene_state.hpp"

namespace tsr::embree {

// The alpha of a triangle of an instance at barycentrics (b1, b2).
inline float alphaAt(const InstanceView& v, std::uint32_t prim, float b1, float b2) {
  const ResolvedMaterial& m = *v.material;
  float alpha = m.material.opacity;
  if (m.baseColorTexture) {
    glm::vec2 uv(b1, b2);
    const MeshData& mesh = *v.mesh;
    if (!mesh.uvs.empty()) {
      const std::uint32_t* idx = &mesh.indices[3 * std::size_t(prim)];
      uv = (1.0f - b1 - b2) * mesh.uvs[idx[0]] + b1 * mesh.uvs[idx[1]] + b2 * mesh.uvs[idx[2]];
    }
    alpha *= m.baseColorTexture->sampleBilinear(m.material.baseColorUv(uv)).w;
  }
  return alpha;
}

// A number in [0, 1) that depends on the ray and the triangle only.
inline float hitKey(const float (&ray)[6], std::uint32_t instance, std::uint32_t prim) {
  std::uint64_t h = (std::uint64_t(instance) << 32) ^ prim;
  for (float f : ray) {
    h ^= std::bit_cast<std::uint32_t>(f) + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
    h = (h ^ (h >> 31)) * 0xbf58476d1ce4e5b9ull;
  }
  h ^= h >> 29;
  return float(h >> 40) * 0x1p-24f;
}

// True when the ray goes on through the surface at this candidate hit.
inline bool passesThrough(const InstanceView& v, std::uint32_t prim, float b1, float b2, float key) {
  const Material& m = v.material->material;
  const float alpha = alphaAt(v, prim, b1, b2);
  return m.alphaMode == AlphaMode::Mask ? alpha < m.alphaCutoff : key >= alpha;
}

// True when a context filter drops candidate i of its call, a hit on
// instance `inst`: the material's alpha cuts the hit away or lets it pass.
inline bool alphaRejects(const SceneState& s, std::uint32_t inst, const RTCFilterFunctionNArguments* args, unsigned i) {
  if (inst >= s.views.size() || !s.views[inst].material || !s.views[inst].material->alphaTested) return false;
  const unsigned n = args->N;
  const float ray[6] = {RTCRayN_org_x(args->ray, n, i), RTCRayN_org_y(args->ray, n, i), RTCRayN_org_z(args->ray, n, i),
                        RTCRayN_dir_x(args->ray, n, i), RTCRayN_dir_y(args->ray, n, i), RTCRayN_dir_z(args->ray, n, i)};
  const std::uint32_t prim = RTCHitN_primID(args->hit, n, i);
  return passesThrough(s.views[inst], prim, RTCHitN_u(args->hit, n, i), RTCHitN_v(args->hit, n, i),
                       hitKey(ray, inst, prim));
}

}  // namespace tsr::embree
