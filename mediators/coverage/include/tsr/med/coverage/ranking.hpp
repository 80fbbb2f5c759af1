#pragma once
// Objects ranked by the pixels they cover, from any back-end's "id" output,
// so the ranking can be recomputed from a frame buffer alone.
//
// The id output holds a scene ContainerId per pixel as floats: .r = id mod
// 2^24 and .g = id / 2^24 (integer parts), both exact in a float, so ids
// below 2^48 survive; for ids below 2^24, .r alone is the id. .a is 1 where
// an object was seen, and the whole pixel is 0 on the background.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec4.hpp>

#include "tsr/med/frame_buffer.hpp"
#include "tsr/med/scene_flattening.hpp"
#include "tsr/sg/scene.hpp"

namespace tsr::med {

inline constexpr const char* kIdOutput = "id";

glm::vec4 encodeObjectId(sg::ContainerId id);
// Throws std::invalid_argument for values no encodeObjectId produces.
sg::ContainerId decodeObjectId(const glm::vec4& value);

struct RankedObject {
  sg::ContainerId id = sg::kNoContainer;
  // The container's name; for an unnamed Transform, the name of its first
  // named Geometry child; empty if the id is no longer in the scene.
  std::string name;
  std::uint64_t pixels = 0;
  double fraction = 0.0;  // of all the frame buffer's pixels, background included
  bool operator==(const RankedObject&) const = default;
};

// The object an instance of a geometry counts for, and whose id the id
// output holds: the nearest Transform on its path, else the Geometry itself.
sg::ContainerId objectOf(const sg::Scene& scene, const FlatNode& instance);

// By pixels descending, ties by id ascending; the background is left out.
// Throws std::invalid_argument when `image` has no id output of its size.
std::vector<RankedObject> rankObjects(const FrameBuffer& image, const sg::Scene& scene);
// Pixels of the id output that show the background.
std::uint64_t backgroundPixels(const FrameBuffer& image);

}  // namespace tsr::med
