#pragma once
// The scene graph as back-ends want it: every geometry instance with one
// world matrix (the product of the transforms on its path), every light
// likewise, and for each group or transform the instances and lights below
// it, so a transform edit touches exactly those.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include <glm/mat4x4.hpp>

#include "tsr/sg/node_world.hpp"
#include "tsr/sg/scene.hpp"

namespace tsr::med {

class FlatteningError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Matches an instance or light across re-flattenings: a hash of its path
// plus its occurrence (the smallest count that makes the key unique within
// one flattening, so repeated children and hash collisions stay apart).
using FlatKey = std::uint64_t;

struct FlatNode {
  sg::ContainerId id = sg::kNoContainer;  // the geometry or light
  std::vector<sg::ContainerId> path;      // from the root down to, not including, id
  FlatKey key = 0;
  glm::mat4 world{1.0f};
  // Some Transform on the path moves over the frame interval: the world
  // matrix at its end is worldMatrix(scene, path, sg::FrameTime::End).
  bool moves = false;
};

struct FlatScene {
  std::vector<FlatNode> instances;  // geometries
  std::vector<FlatNode> lights;
  // For a Group or Transform: indices into instances / lights below it.
  std::unordered_map<sg::ContainerId, std::vector<std::uint32_t>> instancesUnder;
  std::unordered_map<sg::ContainerId, std::vector<std::uint32_t>> lightsUnder;
};

// Walks from `root` (none: every root). Throws FlatteningError when the
// number of instances would exceed `maxInstances` (instancing can multiply).
FlatScene flatten(const sg::Scene& scene, sg::ContainerId root, std::size_t maxInstances = 50'000'000);
// The world matrix of a path, from the scene's current transforms, at the
// frame's time or at the end of its interval.
glm::mat4 worldMatrix(const sg::Scene& scene, const std::vector<sg::ContainerId>& path,
                      sg::FrameTime when = sg::FrameTime::Now);
// Whether some Transform on the path moves over the frame interval.
bool pathMoves(const sg::Scene& scene, const std::vector<sg::ContainerId>& path);

}  // namespace tsr::med
