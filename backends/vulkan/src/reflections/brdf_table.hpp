#pragma once

#include <glm/vec2.hpp>

#include <cstdint>
#include <vector>

namespace tsr::vk {

// The split-sum table of image-based lighting (Karis 2013): for n.v =
// (i + 0.5) / size along x and roughness = (j + 0.5) / size along y, the
// GGX specular's directional albedo split by Schlick's Fresnel as
// F0 * A + B, with the shader's D and height-correlated Smith G2
// (alpha = roughness^2). Integrated by importance sampling the GGX normal
// distribution over a Hammersley set, so it is the same on every run.
std::vector<glm::vec2> splitSumTable(std::uint32_t size, std::uint32_t samples = 512);

// Per roughness row of such a table, the albedo with F = 1 (A + B)
// averaged over the hemisphere, 2 int E(c) c dc by the midpoint rule: the
// E_avg of Kulla and Conty's multiple-scattering term.
std::vector<float> averageAlbedoByRow(const std::vector<glm::vec2>& table, std::uint32_t size);

}  // namespace tsr::vk
