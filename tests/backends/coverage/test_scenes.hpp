#pragma once
// Small scenes for the coverage tests, built so that quad edges fall
// half-way between pixel centres: exact pixel counts are then robust.
#include <cstdint>
#include <random>

#include "tsr/cov/embree_id_renderer.hpp"

namespace tsr::cov::test {

// An axis-aligned quad in the plane z, facing +Z.
MeshData quad(float x0, float x1, float y0, float y1, float z);

// Camera at the origin looking down -Z, window [-1,1]^2 at near 1.
Camera straightCamera();

// `count` instances of a few meshes (quads, boxes, random triangles) placed
// at random in front of straightCamera(), object ids 1..objects; the same
// seed gives the same scene.
struct RandomScene {
  std::vector<MeshData> meshes;
  std::vector<Instance> instances;  // mesh ids index `meshes`
};
RandomScene randomScene(std::uint32_t seed, std::uint32_t count, std::uint32_t objects);
// Adds the scene to a renderer; returns the instance handles in order.
std::vector<InstanceId> load(IdRenderer& renderer, const RandomScene& scene);

}  // namespace tsr::cov::test
