#pragma once

#include <cstdint>

namespace tsr::cov {

// Handles into an IdRenderer's scene. Distinct enum types so a mesh handle
// cannot be passed where an instance handle is expected; never reused
// within one renderer.
enum class MeshId : std::uint32_t {};
enum class InstanceId : std::uint32_t {};

template <class Id>
constexpr std::uint32_t index(Id id) {
  return static_cast<std::uint32_t>(id);
}

// The caller's name for what an instance shows; several instances may share
// one (their pixels add up). 0 is reserved for the background.
using ObjectId = std::uint32_t;
inline constexpr ObjectId kBackground = 0;

}  // namespace tsr::cov
