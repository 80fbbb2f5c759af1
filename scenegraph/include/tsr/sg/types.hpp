#pragma once
// The scene graph's basic vocabulary: ids, container types, field numbers.
#include <cstdint>
#include <string_view>

#include <glm/glm.hpp>

namespace tsr::sg {

// Stable per-scene id; 0 means "no container" in reference fields.
using ContainerId = std::uint64_t;
inline constexpr ContainerId kNoContainer = 0;

// Fields are numbered per container type, 0 and 1 being every container's
// name and attachments; a mask holds one bit per field.
using FieldIndex = std::uint8_t;
using FieldMask = std::uint64_t;
inline constexpr unsigned kMaxFields = 64;
constexpr FieldMask fieldBit(FieldIndex f) { return FieldMask{1} << f; }

// The wire numbers of the container types; never renumber, only append
// (and bump the protocol version when you do).
enum class ContainerType : std::uint8_t {
  Group = 1,
  Transform = 2,
  Geometry = 3,
  Image = 4,
  SimpleMaterial = 5,
  SurfaceMaterial = 6,
  Light = 7,
  Camera = 8,
  Background = 9,
  VolumeMaterial = 10,
};
inline constexpr unsigned kContainerTypeCount = 10;

// A set of container types, used to say what a reference field may name.
using TypeSet = std::uint32_t;
constexpr TypeSet typeBit(ContainerType t) { return TypeSet{1} << static_cast<unsigned>(t); }
// Cameras are nodes: a camera under an animated Transform moves with it.
inline constexpr TypeSet kNodeTypes = typeBit(ContainerType::Group) | typeBit(ContainerType::Transform) |
                                      typeBit(ContainerType::Geometry) | typeBit(ContainerType::Light) |
                                      typeBit(ContainerType::Camera);
inline constexpr TypeSet kMaterialTypes =
    typeBit(ContainerType::SimpleMaterial) | typeBit(ContainerType::SurfaceMaterial);
inline constexpr TypeSet kImageTypes = typeBit(ContainerType::Image);
inline constexpr TypeSet kVolumeTypes = typeBit(ContainerType::VolumeMaterial);

// Types whose first own field is a children list.
constexpr bool isParentType(ContainerType t) { return t == ContainerType::Group || t == ContainerType::Transform; }
constexpr bool isKnownType(std::uint64_t raw) { return raw >= 1 && raw <= kContainerTypeCount; }
std::string_view typeName(ContainerType t);

using Vec2 = glm::vec2;
using Vec3 = glm::vec3;
using Vec4 = glm::vec4;
using Mat4 = glm::mat4;  // column-major, as glm and glTF store it

}  // namespace tsr::sg
