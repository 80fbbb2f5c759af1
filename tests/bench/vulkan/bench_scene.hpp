#pragma once

#include "tsr/vk/mesh.hpp"
#include "tsr/vk/vocabulary.hpp"

#include <glm/mat4x4.hpp>

#include <cstdint>
#include <vector>

namespace tsr::vk::bench {

// The benchmark's content: three shared meshes of a few thousand triangles
// (sphere, subdivided cube, torus) and a 100 x 100 grid of instances cycling
// through them, with a camera that sees the whole grid at an angle.
struct BenchScene {
  std::vector<MeshData> meshes;
  std::vector<std::uint32_t> instanceMesh;  // per instance
  std::vector<glm::mat4> instanceTransform;
  Camera camera;

  std::uint64_t trianglesPerFrame() const;
};

BenchScene makeBenchScene(std::uint32_t instances, std::uint32_t width, std::uint32_t height);

}  // namespace tsr::vk::bench
