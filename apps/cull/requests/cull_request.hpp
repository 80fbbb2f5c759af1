#pragma once
// The JSON of POST /v1/cull, read and checked (a person's mistakes and a
// stranger's tricks alike get a CullRequestError naming the field), and
// the answer written back.
#include <stdexcept>
#include <string>

#include "cull_query.hpp"

namespace tsr::app {

class CullRequestError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

inline constexpr std::uint32_t kMaxCullSide = 4096;

// {"camera": {"position": [x,y,z], "target": [x,y,z], "up": [x,y,z],
// "fov": degrees}, "width": W, "height": H, "max_objects": K}; up defaults
// to +Y, fov to 45, max_objects to `maxObjects`, which also bounds it.
CullQuery parseCullRequest(const std::string& body, std::uint32_t maxObjects);
std::string cullAnswerJson(const CullAnswer& answer);

}  // namespace tsr::app
