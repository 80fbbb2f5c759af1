#pragma once
// Picks the emissive triangle to sample for direct light at a shading
// point by how much each could give there: a bounding-volume hierarchy
// over the emitter triangles whose nodes bound position, emitted power
// and the cone of directions their normals span (Conty Estevez & Kulla
// 2018, "Importance Sampling of Many Lights with Adaptive Tree Splitting";
// the node importance of pbrt-v4's BVHLightSampler). Traversal picks a
// child by its importance at the point, so a lamp far away, behind the
// point or facing away from it is rarely chosen; the probability of any
// one triangle is recomputed along its path from the root (pmf), which is
// what a BSDF ray that hits it needs for MIS. Private to the back-end.
#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace tsr::embree {

struct EmitterTriangle;

// A cone of directions: axis w, half-angle with cosine cosTheta (-1: the
// whole sphere).
struct DirectionCone {
  glm::vec3 w{0.0f, 0.0f, 1.0f};
  float cosTheta = 1.0f;
  bool empty = true;
};

class LightTree {
 public:
  LightTree() = default;
  // power[i]: emitted power of triangle i (0: never picked).
  LightTree(std::span<const EmitterTriangle> triangles, std::span<const float> power);

  bool empty() const { return nodes_.empty(); }

  // Picks a triangle for point p with normal n (zero in a medium: no cosine
  // bound) and its probability; false when none can light p.
  bool sample(const glm::vec3& p, const glm::vec3& n, float u, std::uint32_t& triangle, float& probability) const;
  // The probability with which sample(p, n, ...) picks `triangle`.
  float pmf(const glm::vec3& p, const glm::vec3& n, std::uint32_t triangle) const;

 private:
  struct Node {
    glm::vec3 lo{0.0f}, hi{0.0f};
    DirectionCone cone;
    // Kept from the build for importance(), which runs at every vertex.
    glm::vec3 centre{0.0f};
    float halfDiagonal = 0.0f;
    float sinTheta = 0.0f;  // of the cone
    float power = 0.0f;
    // Interior: the second child's index (the first follows the node);
    // leaf: its first entry in order_, `count` of them (more than one only
    // where the tree would grow deeper than a trail holds).
    std::uint32_t index = 0;
    std::uint32_t count = 0;  // 0: interior
  };
  float importance(const Node& node, const glm::vec3& p, const glm::vec3& n) const;
  std::uint32_t build(std::size_t begin, std::size_t end, std::span<const EmitterTriangle> triangles,
                      std::uint64_t trail, int depth);

  std::vector<Node> nodes_;
  std::vector<std::uint32_t> order_;  // triangles, leaf by leaf
  std::vector<float> power_;          // indexed by triangle
  // Per triangle: the child taken at each level from the root (bit d set:
  // second child at depth d), with a leading 1 marking the depth.
  std::vector<std::uint64_t> trails_;
};

}  // namespace tsr::embree
