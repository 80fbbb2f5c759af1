#pragma once
// Procedural meshes for the built-in scenes, with normals and uvs.
#include "parsed_scene.hpp"

namespace tsr::sg::shapes {

parsed::Primitive sphere(const Vec3& center, float radius, int rings);
parsed::Primitive box(const Vec3& halfExtent);
parsed::Primitive torus(float majorRadius, float minorRadius, int majorSegments, int minorSegments);
// Appends a planar quad (corners in order) as two triangles.
void appendQuad(parsed::Primitive& mesh, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

}  // namespace tsr::sg::shapes
