#pragma once
// What a mesh's indices draw, in every back-end that takes meshes: three
// indices a triangle, two a line segment, one a point. Lines and points are
// one pixel wide (glTF's widths) and unlit: they have no surface to light.
#include <cstddef>
#include <cstdint>

namespace tsr::backend {

enum class Primitive : std::uint8_t { Triangles, Lines, Points };

constexpr std::size_t indicesPer(Primitive p) { return p == Primitive::Lines ? 2 : p == Primitive::Points ? 1 : 3; }

}  // namespace tsr::backend
