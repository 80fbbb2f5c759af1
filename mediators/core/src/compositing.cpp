#include "tsr/med/compositing.hpp"

#include <algorithm>
#include <stdexcept>

#include <glm/glm.hpp>

namespace tsr::med {

namespace {

// Dubois, "A projection method to generate anaglyph stereo images" (ICASSP
// 2001), red/cyan matrices for linear RGB (rows: output R, G, B). They are
// the least-squares fit, for typical filter and display spectra, of the
// colours seen through each filter to those each eye's image should show.
constexpr float kDuboisLeft[3][3] = {
    {0.4561f, 0.500484f, 0.176381f}, {-0.0400822f, -0.0378246f, -0.0157589f}, {-0.0152161f, -0.0205971f, -0.00546856f}};
constexpr float kDuboisRight[3][3] = {
    {-0.0434706f, -0.0879388f, -0.00155529f}, {0.378476f, 0.73364f, -0.0184503f}, {-0.0721527f, -0.112961f, 1.2264f}};

glm::vec3 dubois(const glm::vec4& l, const glm::vec4& r) {
  glm::vec3 out;
  for (int row = 0; row < 3; ++row) {
    float v = 0;
    for (int c = 0; c < 3; ++c) v += kDuboisLeft[row][c] * l[c] + kDuboisRight[row][c] * r[c];
    out[row] = std::clamp(v, 0.0f, 1.0f);
  }
  return out;
}

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

FrameBuffer anaglyph(const FrameBuffer& left, const FrameBuffer& right, AnaglyphMethod method) {
  requireSameSize(left, right, "anaglyph");
  FrameBuffer out(left.width, left.height);
  for (std::size_t i = 0; i < out.colour.size(); ++i) {
    const glm::vec3 rgb = method == AnaglyphMethod::Dubois
                              ? dubois(left.colour[i], right.colour[i])
                              : glm::vec3(left.colour[i].r, right.colour[i].g, right.colour[i].b);
    out.colour[i] = glm::vec4(rgb, std::max(left.colour[i].a, right.colour[i].a));
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
