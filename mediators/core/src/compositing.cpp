#include "tsr/med/compositing.hpp"

#include <algorithm>
#include <stdexcept>

#include <glm/glm.hpp>

namespace tsr::med {

namespace {
void requireSameSize(const FrameBuffer& a, const FrameBuffer& b, const char* what) {
  if (a.width != b.width || a.height != b.height) throw std::invalid_argument(std::string(what) + ": sizes differ");
}
}  // namespace

void compositeByDepth(FrameBuffer& base, const FrameBuffer& layer) {
  requireSameSize(base, layer, "compositeByDepth");
  for (std::size_t i = 0; i < base.colour.size(); ++i) {
    bool layerInFront = layer.depth[i] <= base.depth[i];
    const glm::vec4& nearC = layerInFront ? layer.colour[i] : base.colour[i];
    const glm::vec4& farC = layerInFront ? base.colour[i] : layer.colour[i];
    float a = nearC.a;
    glm::vec3 rgb = glm::vec3(nearC) * a + glm::vec3(farC) * (1.0f - a);
    // Uncovered pixels (alpha 0 on both) keep the far layer's background colour.
    if (a == 0.0f) rgb = glm::vec3(farC);
    base.colour[i] = glm::vec4(rgb, a + farC.a * (1.0f - a));
    // Depth of what is seen: a fully transparent near layer does not hide the far one.
    if (a > 0.0f && layer.depth[i] < base.depth[i]) base.depth[i] = layer.depth[i];
  }
}

FrameBuffer anaglyph(const FrameBuffer& left, const FrameBuffer& right) {
  requireSameSize(left, right, "anaglyph");
  FrameBuffer out(left.width, left.height);
  for (std::size_t i = 0; i < out.colour.size(); ++i) {
    out.colour[i] = glm::vec4(left.colour[i].r, right.colour[i].g, right.colour[i].b,
                              std::max(left.colour[i].a, right.colour[i].a));
    out.depth[i] = std::min(left.depth[i], right.depth[i]);
  }
  return out;
}

FrameBuffer sideBySide(const FrameBuffer& left, const FrameBuffer& right) {
  requireSameSize(left, right, "sideBySide");
  FrameBuffer out(left.width * 2, left.height);
  for (std::uint32_t y = 0; y < left.height; ++y)
    for (std::uint32_t x = 0; x < left.width; ++x) {
      out.colour[out.index(x, y)] = left.colour[left.index(x, y)];
      out.depth[out.index(x, y)] = left.depth[left.index(x, y)];
      out.colour[out.index(x + left.width, y)] = right.colour[right.index(x, y)];
      out.depth[out.index(x + left.width, y)] = right.depth[right.index(x, y)];
    }
  return out;
}

}  // namespace tsr::med
