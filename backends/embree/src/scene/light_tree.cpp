#include "scene/light_tree.hpp"

#include "scene/scene_state.hpp"
#include "tsr/embree/sampling.hpp"

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <numeric>

namespace tsr::embree {

namespace {

constexpr int kBuckets = 12;
// A trail holds one bit a level below its leading marker bit.
constexpr int kMaxDepth = 62;

float safeSqrt(float x) { return std::sqrt(std::max(0.0f, x)); }
float safeAcos(float x) { return std::acos(std::clamp(x, -1.0f, 1.0f)); }

DirectionCone wholeSphere() { return {glm::vec3(0.0f, 0.0f, 1.0f), -1.0f, false}; }

// The smallest cone holding both (pbrt-v4's DirectionCone Union).
DirectionCone unite(const DirectionCone& a, const DirectionCone& b) {
  if (a.empty) return b;
  if (b.empty) return a;
  const float thetaA = safeAcos(a.cosTheta), thetaB = safeAcos(b.cosTheta);
  const float thetaD = safeAcos(glm::dot(a.w, b.w));
  if (std::min(thetaD + thetaB, kPi) <= thetaA) return a;
  if (std::min(thetaD + thetaA, kPi) <= thetaB) return b;
  const float thetaO = 0.5f * (thetaA + thetaD + thetaB);
  if (thetaO >= kPi) return wholeSphere();
  const glm::vec3 axis = glm::cross(a.w, b.w);
  const float len = glm::length(axis);
  if (!(len > 1e-7f)) return wholeSphere();
  const glm::vec3 w = glm::angleAxis(thetaO - thetaA, axis / len) * a.w;
  return {glm::normalize(w), std::cos(thetaO), false};
}

// Orientation measure of a cone of normals emitting into a hemisphere
// each (pbrt-v4's M_Omega with theta_e = pi/2).
float orientationMeasure(const DirectionCone& c) {
  const float thetaO = safeAcos(c.cosTheta);
  const float thetaW = std::min(thetaO + 0.5f * kPi, kPi);
  const float sinO = std::sin(thetaO);
  return 2.0f * kPi * (1.0f - c.cosTheta) +
         0.5f * kPi * (2.0f * thetaW * sinO - std::cos(thetaO - 2.0f * thetaW) - 2.0f * thetaO * sinO + c.cosTheta);
}

float surfaceArea(const glm::vec3& lo, const glm::vec3& hi) {
  const glm::vec3 d = glm::max(hi - lo, glm::vec3(0.0f));
  return 2.0f * (d.x * d.y + d.y * d.z + d.z * d.x);
}

struct Bounds {
  glm::vec3 lo{std::numeric_limits<float>::max()}, hi{-std::numeric_limits<float>::max()};
  DirectionCone cone;
  float power = 0.0f;
  void add(const Bounds& b) {
    lo = glm::min(lo, b.lo);
    hi = glm::max(hi, b.hi);
    cone = unite(cone, b.cone);
    power += b.power;
  }
  float cost() const { return power * orientationMeasure(cone) * surfaceArea(lo, hi); }
};

Bounds boundsOf(const EmitterTriangle& t, float power) {
  Bounds b;
  const glm::vec3 p1 = t.p0 + t.e1, p2 = t.p0 + t.e2;
  b.lo = glm::min(t.p0, glm::min(p1, p2));
  b.hi = glm::max(t.p0, glm::max(p1, p2));
  b.cone = {t.normal, 1.0f, false};
  b.power = power;
  return b;
}

glm::vec3 centroid(const EmitterTriangle& t) { return t.p0 + (t.e1 + t.e2) * (1.0f / 3.0f); }

}  // namespace

LightTree::LightTree(std::span<const EmitterTriangle> triangles, std::span<const float> power)
    : power_(power.begin(), power.end()), trails_(triangles.size(), 0) {
  for (std::uint32_t i = 0; i < triangles.size(); ++i)
    if (power[i] > 0.0f && std::isfinite(power[i]) && triangles[i].area > 0.0f) order_.push_back(i);
  if (order_.empty()) return;
  nodes_.reserve(2 * order_.size());
  build(0, order_.size(), triangles, 1, 0);
}

// Binned split by the surface area orientation heuristic (Conty Estevez &
// Kulla, eq. 2, pbrt-v4's EvaluateCost) over the three axes.
std::uint32_t LightTree::build(std::size_t begin, std::size_t end, std::span<const EmitterTriangle> triangles,
                               std::uint64_t trail, int depth) {
  Bounds all, centres;
  for (std::size_t i = begin; i < end; ++i) {
    const std::uint32_t t = order_[i];
    all.add(boundsOf(triangles[t], power_[t]));
    const glm::vec3 c = centroid(triangles[t]);
    centres.lo = glm::min(centres.lo, c);
    centres.hi = glm::max(centres.hi, c);
  }
  const auto index = std::uint32_t(nodes_.size());
  Node node{all.lo, all.hi, all.cone};
  node.centre = 0.5f * (all.lo + all.hi);
  node.halfDiagonal = 0.5f * glm::length(all.hi - all.lo);
  node.sinTheta = safeSqrt(1.0f - all.cone.cosTheta * all.cone.cosTheta);
  node.power = all.power;
  node.index = std::uint32_t(begin);
  node.count = std::uint32_t(end - begin);
  nodes_.push_back(node);
  if (end - begin == 1 || depth >= kMaxDepth) {
    for (std::size_t i = begin; i < end; ++i) trails_[order_[i]] = trail;
    return index;
  }

  const glm::vec3 extent = centres.hi - centres.lo;
  const float maxExtent = std::max(extent.x, std::max(extent.y, extent.z));
  float bestCost = std::numeric_limits<float>::infinity();
  int bestAxis = -1, bestBucket = -1;
  auto bucketOf = [&](std::uint32_t t, int axis) {
    const float f = (centroid(triangles[t])[axis] - centres.lo[axis]) / extent[axis];
    return std::clamp(int(f * kBuckets), 0, kBuckets - 1);
  };
  for (int axis = 0; axis < 3; ++axis) {
    if (!(extent[axis] > 0.0f)) continue;
    std::array<Bounds, kBuckets> buckets;
    for (std::size_t i = begin; i < end; ++i) {
      const std::uint32_t t = order_[i];
      buckets[bucketOf(t, axis)].add(boundsOf(triangles[t], power_[t]));
    }
    // Thin boxes split across their long side are favoured (pbrt's Kr).
    const float regularise = maxExtent / extent[axis];
    for (int split = 0; split < kBuckets - 1; ++split) {
      Bounds below, above;
      for (int b = 0; b <= split; ++b) below.add(buckets[b]);
      for (int b = split + 1; b < kBuckets; ++b) above.add(buckets[b]);
      if (below.power <= 0.0f && above.power <= 0.0f) continue;
      const float cost = regularise * (below.cost() + above.cost());
      if (cost < bestCost) bestCost = cost, bestAxis = axis, bestBucket = split;
    }
  }
  std::size_t mid = begin;
  if (bestAxis >= 0) {
    mid = std::size_t(std::partition(order_.begin() + std::ptrdiff_t(begin), order_.begin() + std::ptrdiff_t(end),
                                     [&](std::uint32_t t) { return bucketOf(t, bestAxis) <= bestBucket; }) -
                      order_.begin());
  }
  if (mid == begin || mid == end) {  // all centroids alike: halve the list
    mid = (begin + end) / 2;
  }
  nodes_[index].count = 0;
  build(begin, mid, triangles, trail << 1, depth + 1);
  const std::uint32_t second = build(mid, end, triangles, (trail << 1) | 1u, depth + 1);
  nodes_[index].index = second;
  return index;
}

// An upper bound on what the node's triangles can send to p (pbrt-v4's
// LightBounds::Importance, emitters one-sided: theta_e = pi/2).
float LightTree::importance(const Node& node, const glm::vec3& p, const glm::vec3& n) const {
  const glm::vec3 toPoint = p - node.centre;
  const float halfDiagonal = node.halfDiagonal;
  const float squared = glm::dot(toPoint, toPoint);
  const float d2 = std::max(squared, halfDiagonal * halfDiagonal);
  const float dist = std::sqrt(squared);
  const glm::vec3 wi = dist > 0.0f ? toPoint / dist : glm::vec3(0.0f);
  // cos and sin of a - b, clamped to 1 and 0 when a < b.
  auto cosSub = [](float sinA, float cosA, float sinB, float cosB) {
    return cosA > cosB ? 1.0f : cosA * cosB + sinA * sinB;
  };
  auto sinSub = [](float sinA, float cosA, float sinB, float cosB) {
    return cosA > cosB ? 0.0f : sinA * cosB - cosA * sinB;
  };
  // The directions the box subtends from p (its bounding sphere).
  float cosB = -1.0f;
  if (dist * dist > halfDiagonal * halfDiagonal) cosB = safeSqrt(1.0f - halfDiagonal * halfDiagonal / (dist * dist));
  const float sinB = safeSqrt(1.0f - cosB * cosB);

  const float cosW = glm::dot(node.cone.w, wi), sinW = safeSqrt(1.0f - cosW * cosW);
  const float cosO = node.cone.cosTheta, sinO = node.sinTheta;
  const float cosX = cosSub(sinW, cosW, sinO, cosO), sinX = sinSub(sinW, cosW, sinO, cosO);
  const float cosThetaP = cosSub(sinX, cosX, sinB, cosB);
  if (cosThetaP <= 0.0f) return 0.0f;  // every normal faces away from p
  float value = node.power * cosThetaP / d2;
  if (n != glm::vec3(0.0f)) {
    const float cosI = std::abs(glm::dot(wi, n)), sinI = safeSqrt(1.0f - cosI * cosI);
    value *= cosSub(sinI, cosI, sinB, cosB);
  }
  return std::isfinite(value) ? std::max(value, 0.0f) : 0.0f;
}

bool LightTree::sample(const glm::vec3& p, const glm::vec3& n, float u, std::uint32_t& triangle,
                       float& probability) const {
  if (nodes_.empty() || !(importance(nodes_[0], p, n) > 0.0f)) return false;
  std::uint32_t at = 0;
  float prob = 1.0f;
  while (nodes_[at].count == 0) {
    const std::uint32_t a = at + 1, b = nodes_[at].index;
    const float ia = importance(nodes_[a], p, n), ib = importance(nodes_[b], p, n);
    if (!(ia + ib > 0.0f)) return false;
    // The same expressions as pmf(), so MIS sees the probability exactly.
    const float pa = ia / (ia + ib), pb = ib / (ia + ib);
    if (u < pa) {
      at = a;
      prob *= pa;
      u = std::min(u / pa, 0x1.fffffep-1f);
    } else {
      at = b;
      prob *= pb;
      u = std::min((u - pa) / (1.0f - pa), 0x1.fffffep-1f);
    }
  }
  const Node& leaf = nodes_[at];
  float target = u * leaf.power;
  std::uint32_t i = leaf.index, last = leaf.index + leaf.count - 1;
  for (; i < last && target >= power_[order_[i]]; ++i) target -= power_[order_[i]];
  triangle = order_[i];
  probability = prob * power_[triangle] / leaf.power;
  return probability > 0.0f;
}

float LightTree::pmf(const glm::vec3& p, const glm::vec3& n, std::uint32_t triangle) const {
  if (triangle >= trails_.size() || trails_[triangle] == 0 || !(importance(nodes_[0], p, n) > 0.0f)) return 0.0f;
  const std::uint64_t trail = trails_[triangle];
  int level = 63 - std::countl_zero(trail);  // bits below the marker
  std::uint32_t at = 0;
  float prob = 1.0f;
  while (nodes_[at].count == 0) {
    const std::uint32_t a = at + 1, b = nodes_[at].index;
    const float ia = importance(nodes_[a], p, n), ib = importance(nodes_[b], p, n);
    if (!(ia + ib > 0.0f)) return 0.0f;
    const bool second = (trail >> --level) & 1u;
    prob *= (second ? ib : ia) / (ia + ib);
    at = second ? b : a;
  }
  return prob * power_[triangle] / nodes_[at].power;
}

}  // namespace tsr::embree
