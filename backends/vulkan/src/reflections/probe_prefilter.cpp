#include "reflections/probe_prefilter.hpp"
#include "reflections/ggx_prefilter.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace tsr::vk {

namespace {

// One square face per layer, radiance only.
struct Cube {
  std::uint32_t size = 0;
  std::vector<glm::vec3> texels;  // face-major, rows top to bottom

  const glm::vec3& at(std::uint32_t face, std::uint32_t x, std::uint32_t y) const {
    return texels[(std::size_t(face) * size + y) * size + x];
  }
  // Nearest texel in direction d (not necessarily unit).
  const glm::vec3& lookup(const glm::vec3& d) const {
    const glm::vec3 a = glm::abs(d);
    const std::uint32_t face = a.x >= a.y && a.x >= a.z ? (d.x > 0 ? 0 : 1)
                               : a.y >= a.z             ? (d.y > 0 ? 2 : 3)
                                                        : (d.z > 0 ? 4 : 5);
    const glm::vec3& forward = kProbeFaceForward[face];
    const glm::vec3& up = kProbeFaceUp[face];
    const glm::vec3 right = glm::cross(forward, up);
    const float w = glm::dot(d, forward);
    const float u = 0.5f + 0.5f * glm::dot(d, right) / w, v = 0.5f - 0.5f * glm::dot(d, up) / w;
    const auto texel = [this](float t) { return std::min(size - 1, std::uint32_t(std::max(0.0f, t * float(size)))); };
    return at(face, texel(u), texel(v));
  }
  // Box-averaged to half the size.
  Cube halved() const {
    Cube h{size / 2, std::vector<glm::vec3>(std::size_t(6) * (size / 2) * (size / 2))};
    for (std::uint32_t f = 0; f < 6; ++f)
      for (std::uint32_t y = 0; y < h.size; ++y)
        for (std::uint32_t x = 0; x < h.size; ++x)
          h.texels[(std::size_t(f) * h.size + y) * h.size + x] =
              0.25f *
              (at(f, 2 * x, 2 * y) + at(f, 2 * x + 1, 2 * y) + at(f, 2 * x, 2 * y + 1) + at(f, 2 * x + 1, 2 * y + 1));
    return h;
  }
};

}  // namespace

glm::vec3 probeTexelDirection(std::uint32_t face, float x, float y, std::uint32_t size) {
  const glm::vec3& forward = kProbeFaceForward[face];
  const glm::vec3& up = kProbeFaceUp[face];
  const glm::vec3 right = glm::cross(forward, up);
  const float u = 2.0f * x / float(size) - 1.0f, v = 1.0f - 2.0f * y / float(size);
  return forward + right * u + up * v;
}

std::vector<glm::vec4> prefilterProbe(std::span<const glm::vec4> faces, std::uint32_t size,
                                      const Environment& environment, bool keepClear) {
  Cube cube{size, std::vector<glm::vec3>(faces.size())};
  for (std::uint32_t f = 0; f < 6; ++f)
    for (std::uint32_t y = 0; y < size; ++y)
      for (std::uint32_t x = 0; x < size; ++x) {
        const std::size_t i = (std::size_t(f) * size + y) * size + x;
        const bool background = faces[i].a < -0.5f && !keepClear;  // the faces' clear alpha, -1
        cube.texels[i] = background
                             ? environment.radiance(glm::normalize(probeTexelDirection(f, x + 0.5f, y + 0.5f, size)))
                             : glm::vec3(faces[i]);
      }

  constexpr std::uint32_t n = ProbeLevels::kSize;
  std::vector<glm::vec4> out(std::size_t(n) * ProbeLevels::kHeight);
  // Rougher levels read coarser copies so 64 samples do not alias.
  Cube source = std::move(cube);
  while (source.size > n) source = source.halved();
  for (std::uint32_t k = 1; k <= ProbeLevels::kLevels; ++k) {
    if (k > 2 && source.size > 4) source = source.halved();
    const float roughness = float(k) / float(ProbeLevels::kLevels);
    for (std::uint32_t f = 0; f < 6; ++f)
      for (std::uint32_t y = 0; y < n; ++y)
        for (std::uint32_t x = 0; x < n; ++x) {
          const glm::vec3 r = glm::normalize(probeTexelDirection(f, x + 0.5f, y + 0.5f, n));
          out[((std::size_t(k - 1) * 6 + f) * n + y) * n + x] = glm::vec4(
              ggxPrefiltered(r, roughness, 64, [&source](const glm::vec3& l) { return source.lookup(l); }), 1.0f);
        }
  }
  return out;
}

}  // namespace tsr::vk
