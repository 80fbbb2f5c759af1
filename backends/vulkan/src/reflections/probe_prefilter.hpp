#pragma once
// What the rasterizer's reflection probe gives beyond mirror images: the
// scene in rough reflections, from its faces prefiltered by GGX roughness
// as Environment::prefiltered() does for the background. Computed on the
// host once per probe refresh, not per frame; shaders/probe.glsl reads it.
#include "tsr/vk/environment.hpp"

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace tsr::vk {

// The levels' layout: faces of kSize x kSize, levels 1..kLevels for GGX
// roughness k / kLevels (level 0 is the probe itself), each level's six
// faces stacked vertically in probe.glsl's face order: one image kSize wide.
struct ProbeLevels {
  static constexpr std::uint32_t kSize = 16, kLevels = 4;
  static constexpr std::uint32_t kHeight = kSize * 6 * kLevels;
};

// Per face: the direction it looks along and its up, as the probe is drawn
// (reflection_probe.cpp) and as probe.glsl picks faces from a direction.
inline const glm::vec3 kProbeFaceForward[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
inline const glm::vec3 kProbeFaceUp[6] = {{0, 1, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, -1}, {0, 1, 0}, {0, 1, 0}};

// The direction through texel (x, y) of face f of a cube of size x size
// faces, in probe.glsl's convention (and the one the probe is drawn with).
glm::vec3 probeTexelDirection(std::uint32_t face, float x, float y, std::uint32_t size);

// `faces`: six size x size faces of radiance as the probe drew them, alpha -1
// where nothing was drawn: there the background shows, read from the
// environment (or kept as drawn when `keepClear`, e.g. the fog's colour).
// Returns the levels' kSize x kHeight texels.
std::vector<glm::vec4> prefilterProbe(std::span<const glm::vec4> faces, std::uint32_t size,
                                      const Environment& environment, bool keepClear);

}  // namespace tsr::vk
