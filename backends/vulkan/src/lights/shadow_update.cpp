#include "lights/shadow_update.hpp"

#include <algorithm>
#include <cmath>

namespace tsr::vk {

std::vector<ShadowCaster> shadowCasters(const SceneState& s) {
  std::vector<ShadowCaster> out(s.instances.size());
  for (std::size_t i = 0; i < out.size(); ++i) {
    const InstanceRecord& r = s.instances[i];
    out[i] = {r.transform, r.mesh, r.material, r.alive};
  }
  return out;
}

namespace {

VkRect2D whole(std::uint32_t size) { return {{0, 0}, {size, size}}; }

bool empty(const VkRect2D& r) { return r.extent.width == 0 || r.extent.height == 0; }

VkRect2D unite(const VkRect2D& a, const VkRect2D& b) {
  if (empty(a)) return b;
  if (empty(b)) return a;
  const std::int32_t x0 = std::min(a.offset.x, b.offset.x), y0 = std::min(a.offset.y, b.offset.y);
  const std::int32_t x1 =
      std::max(a.offset.x + std::int32_t(a.extent.width), b.offset.x + std::int32_t(b.extent.width));
  const std::int32_t y1 =
      std::max(a.offset.y + std::int32_t(a.extent.height), b.offset.y + std::int32_t(b.extent.height));
  return {{x0, y0}, {std::uint32_t(x1 - x0), std::uint32_t(y1 - y0)}};
}

}  // namespace

bool overlaps(const VkRect2D& a, const VkRect2D& b) {
  return !empty(a) && !empty(b) && a.offset.x < b.offset.x + std::int32_t(b.extent.width) &&
         b.offset.x < a.offset.x + std::int32_t(a.extent.width) &&
         a.offset.y < b.offset.y + std::int32_t(b.extent.height) &&
         b.offset.y < a.offset.y + std::int32_t(a.extent.height);
}

VkRect2D shadowFootprint(const SceneState& s, std::uint32_t mesh, const glm::mat4& transform, const glm::mat4& viewProj,
                         std::uint32_t size) {
  const MeshRecord& m = s.meshes[mesh];
  const glm::mat4 toClip = viewProj * transform;
  float x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
  for (int c = 0; c < 8; ++c) {
    const glm::vec4 p((c & 1) ? m.boundsMax.x : m.boundsMin.x, (c & 2) ? m.boundsMax.y : m.boundsMin.y,
                      (c & 4) ? m.boundsMax.z : m.boundsMin.z, 1.0f);
    const glm::vec4 clip = toClip * p;
    if (!(clip.w > 1e-6f)) return whole(size);  // behind a spot light's eye: projection does not bound it
    x0 = std::min(x0, clip.x / clip.w);
    x1 = std::max(x1, clip.x / clip.w);
    y0 = std::min(y0, clip.y / clip.w);
    y1 = std::max(y1, clip.y / clip.w);
  }
  // Clip space [-1, 1] to texels, a texel of margin for rasterisation rules.
  auto texel = [&](float ndc) { return (ndc * 0.5f + 0.5f) * float(size); };
  if (!std::isfinite(x0) || !std::isfinite(x1) || !std::isfinite(y0) || !std::isfinite(y1)) return whole(size);
  const float fx0 = std::floor(texel(x0)) - 1.0f, fy0 = std::floor(texel(y0)) - 1.0f;
  const float fx1 = std::ceil(texel(x1)) + 1.0f, fy1 = std::ceil(texel(y1)) + 1.0f;
  const float lim = float(size);
  const auto cx0 = std::int32_t(std::clamp(fx0, 0.0f, lim)), cy0 = std::int32_t(std::clamp(fy0, 0.0f, lim));
  const auto cx1 = std::int32_t(std::clamp(fx1, 0.0f, lim)), cy1 = std::int32_t(std::clamp(fy1, 0.0f, lim));
  if (cx1 <= cx0 || cy1 <= cy0) return {{0, 0}, {0, 0}};
  return {{cx0, cy0}, {std::uint32_t(cx1 - cx0), std::uint32_t(cy1 - cy0)}};
}

std::optional<std::vector<VkRect2D>> shadowRedraw(const ShadowContents& held, const ShadowContents& now,
                                                  const SceneState& s, std::uint32_t size) {
  if (held.scene != now.scene || held.casterEdits != now.casterEdits || held.viewProj != now.viewProj)
    return std::nullopt;
  std::vector<VkRect2D> rects(now.viewProj.size(), VkRect2D{{0, 0}, {0, 0}});
  const std::size_t n = std::max(held.casters.size(), now.casters.size());
  for (std::size_t i = 0; i < n; ++i) {
    const ShadowCaster none{};
    const ShadowCaster& was = i < held.casters.size() ? held.casters[i] : none;
    const ShadowCaster& is = i < now.casters.size() ? now.casters[i] : none;
    if (was == is) continue;
    for (std::size_t layer = 0; layer < rects.size(); ++layer)
      for (const ShadowCaster* c : {&was, &is})
        if (c->alive)
          rects[layer] = unite(rects[layer], shadowFootprint(s, c->mesh, c->transform, now.viewProj[layer], size));
  }
  // A redraw of half the map or more costs about what a whole one does.
  for (const VkRect2D& r : rects)
    if (2 * std::uint64_t(r.extent.width) * r.extent.height >= std::uint64_t(size) * size) return std::nullopt;
  return rects;
}

}  // namespace tsr::vk
