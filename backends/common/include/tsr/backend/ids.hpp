#pragma once

#include <cstdint>

namespace tsr::backend {

// Handles into a back-end's scene. Distinct enum types so a mesh id cannot
// be passed where an instance id is expected. Ids are never reused within
// one scene.
enum class MeshId : std::uint32_t {};
enum class InstanceId : std::uint32_t {};
enum class MaterialId : std::uint32_t {};
enum class TextureId : std::uint32_t {};
enum class LightId : std::uint32_t {};

template <class Id>
constexpr std::uint32_t index(Id id) {
  return static_cast<std::uint32_t>(id);
}

}  // namespace tsr::backend
