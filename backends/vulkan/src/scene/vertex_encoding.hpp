#pragma once
// Compact vertex streams (as glTF's KHR_mesh_quantization and meshoptimizer
// store them): positions and uvs as 16-bit fractions of their mesh's
// bounding box (of positions, of uvs), normals as two 16-bit octahedral
// coordinates. 14 bytes a vertex instead of 32 (16 where the device reads
// no three-component 16-bit vertex format); the shaders decode with
// common.glsl's modelPosition, meshUv and octNormal.
//
// Tolerance: a position moves by at most half a step, (box extent) / 131070
// on each axis (1.5 mm on a 200 m mesh); a uv likewise (a 1024-texel
// texture repeated 16 times across a mesh: an eighth of a texel); a normal
// turns by at most 0.004 degrees (0.0037 measured over 2 M random
// directions).
#include <glm/common.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vector_relational.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>

namespace tsr::vk {

// A mesh's box of positions or of uvs: value = lo + fraction * (hi - lo).
template <class V>
struct BoxQuantization {
  V lo{0.0f};
  V hi{0.0f};

  static BoxQuantization of(std::span<const V> values) {
    if (values.empty()) return {};
    BoxQuantization q{values[0], values[0]};
    for (const V& v : values) {
      q.lo = glm::min(q.lo, v);
      q.hi = glm::max(q.hi, v);
    }
    return q;
  }
  V scale() const { return hi - lo; }
};
using PositionQuantization = BoxQuantization<glm::vec3>;
using UvQuantization = BoxQuantization<glm::vec2>;

using QuantizedPosition = std::array<std::uint16_t, 4>;  // x, y, z, padding (stored or not: Device::positionBytes)
using QuantizedUv = std::array<std::uint16_t, 2>;
using OctNormal = std::array<std::int16_t, 2>;

// The value's 16-bit fraction of the box on each of its axes (the first of N).
template <class V, std::size_t N>
std::array<std::uint16_t, N> quantize(const BoxQuantization<V>& q, const V& v) {
  std::array<std::uint16_t, N> out{};
  const V scale = q.scale();
  for (int a = 0; a < V::length(); ++a) {
    if (!(scale[a] > 0.0f)) continue;  // a flat axis is its lo
    const float f = std::clamp((v[a] - q.lo[a]) / scale[a], 0.0f, 1.0f);
    out[a] = std::uint16_t(std::lround(f * 65535.0f));
  }
  return out;
}

inline QuantizedPosition quantize(const PositionQuantization& q, const glm::vec3& p) {
  return quantize<glm::vec3, 4>(q, p);
}
inline QuantizedUv quantize(const UvQuantization& q, const glm::vec2& uv) { return quantize<glm::vec2, 2>(q, uv); }

inline glm::vec3 dequantize(const PositionQuantization& q, const QuantizedPosition& v) {
  return q.lo + glm::vec3(v[0], v[1], v[2]) / 65535.0f * q.scale();
}
inline glm::vec2 dequantize(const UvQuantization& q, const QuantizedUv& v) {
  return q.lo + glm::vec2(v[0], v[1]) / 65535.0f * q.scale();
}

// The corner (-1, -1) stands for a zero normal (a mesh without normals: the
// fragment shader then shades the flat face), which octahedral coordinates
// cannot otherwise say; every corner is the direction (0, 0, -1), so real
// normals keep (1, 1) and its neighbours.
constexpr OctNormal kNoNormal{-32767, -32767};

inline OctNormal octEncode(const glm::vec3& n) {
  const float l1 = std::abs(n.x) + std::abs(n.y) + std::abs(n.z);
  if (!(l1 > 0.0f) || !std::isfinite(l1)) return kNoNormal;
  float x = n.x / l1, y = n.y / l1;
  if (n.z < 0.0f) {
    const float fx = (1.0f - std::abs(y)) * (x >= 0.0f ? 1.0f : -1.0f);
    const float fy = (1.0f - std::abs(x)) * (y >= 0.0f ? 1.0f : -1.0f);
    x = fx;
    y = fy;
  }
  OctNormal e{std::int16_t(std::lround(std::clamp(x, -1.0f, 1.0f) * 32767.0f)),
              std::int16_t(std::lround(std::clamp(y, -1.0f, 1.0f) * 32767.0f))};
  if (e == kNoNormal) e[1] = -32766;
  return e;
}

inline glm::vec3 octDecode(const OctNormal& e) {
  if (e == kNoNormal) return glm::vec3(0.0f);
  const float x = std::max(float(e[0]) / 32767.0f, -1.0f), y = std::max(float(e[1]) / 32767.0f, -1.0f);
  glm::vec3 n(x, y, 1.0f - std::abs(x) - std::abs(y));
  if (n.z < 0.0f) {
    n.x = (1.0f - std::abs(y)) * (x >= 0.0f ? 1.0f : -1.0f);
    n.y = (1.0f - std::abs(x)) * (y >= 0.0f ? 1.0f : -1.0f);
  }
  return n / std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
}

}  // namespace tsr::vk
