#pragma once
// What one merged change entry asks of a scene adapter, each question named
// (after hdEmbree's IsTopologyDirty / IsPrimvarDirty / IsTransformDirty), so
// a sync phase reads as "if (transformDirty(e)) move it". Entries of
// containers created since the adapter's version answer false where their
// conversion happens elsewhere (placement, or the first lookup).
#include "tsr/sg/changes/merged_changes.hpp"
#include "tsr/sg/scene.hpp"

namespace tsr::med {

using ChangeEntry = sg::MergedChanges::Entry;

// Every geometry field a shaded mesh holds (all but the material binding).
inline constexpr sg::FieldMask kAllMeshFields =
    sg::fieldBit(sg::Geometry::Positions) | sg::fieldBit(sg::Geometry::Normals) | sg::fieldBit(sg::Geometry::Uvs) |
    sg::fieldBit(sg::Geometry::Colors) | sg::fieldBit(sg::Geometry::Indices) | sg::fieldBit(sg::Geometry::Motion) |
    sg::fieldBit(sg::Geometry::Primitive);

inline bool isNode(const ChangeEntry& e) { return (sg::typeBit(e.type) & sg::kNodeTypes) != 0; }
// Surface and volume materials alike: what a geometry's shading is made of.
inline bool isMaterial(const ChangeEntry& e) {
  return (sg::typeBit(e.type) & (sg::kMaterialTypes | sg::kVolumeTypes)) != 0;
}
inline bool isGeometry(const ChangeEntry& e) { return e.type == sg::ContainerType::Geometry; }
inline bool edited(const ChangeEntry& e) { return !e.created && !e.destroyed; }

// The flattened graph changes shape: a node came or went, a parent's
// children changed, or attachments (which may hide a node) changed.
// Cameras are nodes but never flattened: one alone changes nothing here
// (hanging it under a parent changes the parent's children).
inline bool structureDirty(const ChangeEntry& e) {
  if (!isNode(e) || e.type == sg::ContainerType::Camera) return false;
  return e.created || e.destroyed || e.changed(sg::Container::kAttachments) ||
         (sg::isParentType(e.type) && e.changed(sg::Group::Children));
}

// A transform's matrix, or its motion over the frame interval (which
// back-ends that blur motion place too): the instances and lights below it move.
inline bool transformDirty(const ChangeEntry& e) {
  return e.type == sg::ContainerType::Transform &&
         (e.changed(sg::Transform::Matrix) || e.changed(sg::Transform::FrameMotion));
}

// A light's own fields: it is placed again where it stands.
inline bool lightDirty(const ChangeEntry& e) { return e.type == sg::ContainerType::Light && !e.destroyed; }

// A material's values (an existing one; new ones are translated when used).
inline bool materialDirty(const ChangeEntry& e) { return isMaterial(e) && edited(e) && e.mask != 0; }

// An image's pixels, for the textures made from it.
inline bool imageDirty(const ChangeEntry& e) { return e.type == sg::ContainerType::Image && edited(e); }

// A geometry points at another surface or volume material.
inline bool materialBindingDirty(const ChangeEntry& e) {
  return isGeometry(e) && edited(e) && (e.changed(sg::Geometry::Material) || e.changed(sg::Geometry::Volume));
}

// Any of a geometry's fields in `meshFields` (those a back-end's mesh holds).
inline bool meshDirty(const ChangeEntry& e, sg::FieldMask meshFields) {
  return isGeometry(e) && edited(e) && (e.mask & meshFields) != 0;
}

// Only vertex runs of positions or normals changed: the topology stands and
// the mesh can be updated in place, range by range.
inline bool pointsRangeOnly(const ChangeEntry& e, sg::FieldMask meshFields) {
  using G = sg::Geometry;
  const sg::FieldMask ranged = sg::fieldBit(G::Positions) | sg::fieldBit(G::Normals);
  if (!meshDirty(e, meshFields) || (e.mask & meshFields & ~ranged)) return false;
  for (G::Field f : {G::Positions, G::Normals})
    if ((meshFields & sg::fieldBit(f)) && e.changed(f) && !e.rangedEdit(f)) return false;
  return true;
}

// After this entry some back-end mesh, material or texture may be used by
// nothing: something was destroyed, rebound or re-referenced, or the graph
// changed shape. Value edits (a colour, a range of vertices) never orphan.
inline bool mayOrphan(const ChangeEntry& e, const sg::Container* now) {
  if (e.destroyed || structureDirty(e) || materialBindingDirty(e)) return true;
  return isMaterial(e) && now && (e.mask & now->referenceFields()) != 0;
}

}  // namespace tsr::med
