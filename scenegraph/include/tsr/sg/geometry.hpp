#pragma once
// Indexed triangles (or lines, or points: GeometryPrimitive) with optional
// per-vertex normals, uvs and colours. Every
// array can be replaced whole or edited by range; only edited ranges travel.
// The arrays are shared with the change lists and replicas that carry them
// (SharedArray): a process holds one copy of a mesh until someone edits it.
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "tsr/sg/container_of.hpp"

namespace tsr::sg {

// A hint for back-ends: static geometry can get a high-quality, merged
// acceleration structure; animated geometry a refit-friendly one.
enum class GeometryMotion : std::uint8_t { Static, Animated, Count };

// What the indices draw: three a triangle, two a line segment, one a point
// (glTF's modes 4, 1 and 0; strips, loops and fans are made lists on
// import). Lines and points are one pixel wide, as glTF viewers draw them,
// and unlit: they have no surface to light.
enum class GeometryPrimitive : std::uint8_t { Triangles, Lines, Points, Count };

constexpr std::size_t indicesPerPrimitive(GeometryPrimitive p) {
  return p == GeometryPrimitive::Lines ? 2 : p == GeometryPrimitive::Points ? 1 : 3;
}

class Geometry final : public ContainerOf<Geometry, ContainerType::Geometry> {
 public:
  enum Field : FieldIndex {
    Positions = kFirstOwnField,
    Normals,
    Uvs,
    Colors,
    Indices,
    Material,
    Motion,
    Volume,
    Primitive
  };

  const ArrayElements<Vec3>& positions() const { return positions_.get(); }
  const ArrayElements<Vec3>& normals() const { return normals_.get(); }
  const ArrayElements<Vec2>& uvs() const { return uvs_.get(); }
  const ArrayElements<Vec4>& colors() const { return colors_.get(); }
  const ArrayElements<std::uint32_t>& indices() const { return indices_.get(); }
  // The arrays themselves, for a back-end to hold too without a copy (null
  // when empty); the scene copies an array before its next edit.
  std::shared_ptr<const ArrayElements<Vec3>> sharedPositions() const { return positions_.shared(); }
  std::shared_ptr<const ArrayElements<Vec3>> sharedNormals() const { return normals_.shared(); }
  std::shared_ptr<const ArrayElements<Vec2>> sharedUvs() const { return uvs_.shared(); }
  std::shared_ptr<const ArrayElements<std::uint32_t>> sharedIndices() const { return indices_.shared(); }
  ContainerId material() const { return material_; }
  GeometryMotion motion() const { return motion_; }
  // The medium inside the (closed) mesh, beside its surface material.
  ContainerId volume() const { return volume_; }
  GeometryPrimitive primitive() const { return primitive_; }
  // Triangles, segments or points, as primitive() says.
  std::size_t primitiveCount() const { return indices_.size() / indicesPerPrimitive(primitive_); }
  std::size_t triangleCount() const { return primitive_ == GeometryPrimitive::Triangles ? primitiveCount() : 0; }

  void setPositions(std::vector<Vec3> v) { set<&Geometry::positions_>(std::move(v)); }
  void setNormals(std::vector<Vec3> v) { set<&Geometry::normals_>(std::move(v)); }
  void setUvs(std::vector<Vec2> v) { set<&Geometry::uvs_>(std::move(v)); }
  void setColors(std::vector<Vec4> v) { set<&Geometry::colors_>(std::move(v)); }
  void setIndices(std::vector<std::uint32_t> v) { set<&Geometry::indices_>(std::move(v)); }
  void setMaterial(ContainerId m) { set<&Geometry::material_>(m); }
  void setMotion(GeometryMotion m) { set<&Geometry::motion_>(m); }
  void setVolume(ContainerId v) { set<&Geometry::volume_>(v); }
  void setPrimitive(GeometryPrimitive p) { set<&Geometry::primitive_>(p); }
  // Arrays another owner holds (a mapped cache entry's), taken without a
  // copy: checked like any set value, copied before their first edit.
  void setSharedPositions(SharedArray<Vec3> a) { set<&Geometry::positions_>(std::move(a)); }
  void setSharedNormals(SharedArray<Vec3> a) { set<&Geometry::normals_>(std::move(a)); }
  void setSharedUvs(SharedArray<Vec2> a) { set<&Geometry::uvs_>(std::move(a)); }
  void setSharedColors(SharedArray<Vec4> a) { set<&Geometry::colors_>(std::move(a)); }
  void setSharedIndices(SharedArray<std::uint32_t> a) { set<&Geometry::indices_>(std::move(a)); }

  // Range edits: overwrite elements starting at `begin`; lengths do not change.
  void updatePositions(std::size_t begin, std::span<const Vec3> v) { setElements<&Geometry::positions_>(begin, v); }
  void updateNormals(std::size_t begin, std::span<const Vec3> v) { setElements<&Geometry::normals_>(begin, v); }
  void updateUvs(std::size_t begin, std::span<const Vec2> v) { setElements<&Geometry::uvs_>(begin, v); }
  void updateColors(std::size_t begin, std::span<const Vec4> v) { setElements<&Geometry::colors_>(begin, v); }
  void updateIndices(std::size_t begin, std::span<const std::uint32_t> v) {
    setElements<&Geometry::indices_>(begin, v);
  }

  // Why this geometry cannot be rendered as it stands (index out of range,
  // attribute arrays of the wrong length), or nothing. The scene allows such
  // states between edits; adapters check before handing data to a back-end.
  std::optional<std::string> invalidReason() const;

  static constexpr auto fieldSpecs() {
    using M = Geometry;
    return std::tuple{arrayField(Positions, "positions", &M::positions_, &M::setPositions),
                      arrayField(Normals, "normals", &M::normals_, &M::setNormals),
                      arrayField(Uvs, "uvs", &M::uvs_, &M::setUvs),
                      arrayField(Colors, "colors", &M::colors_, &M::setColors),
                      arrayField(Indices, "indices", &M::indices_, &M::setIndices),
                      referenceField(Material, "material", &M::material_, kMaterialTypes, &M::setMaterial),
                      valueField(Motion, "motion", &M::motion_, &M::setMotion),
                      referenceField(Volume, "volume", &M::volume_, kVolumeTypes, &M::setVolume),
                      valueField(Primitive, "primitive", &M::primitive_, &M::setPrimitive)};
  }

 private:
  SharedArray<Vec3> positions_;
  SharedArray<Vec3> normals_;
  SharedArray<Vec2> uvs_;
  SharedArray<Vec4> colors_;
  SharedArray<std::uint32_t> indices_;
  ContainerId material_ = kNoContainer;
  GeometryMotion motion_ = GeometryMotion::Static;
  ContainerId volume_ = kNoContainer;
  GeometryPrimitive primitive_ = GeometryPrimitive::Triangles;
};

}  // namespace tsr::sg
