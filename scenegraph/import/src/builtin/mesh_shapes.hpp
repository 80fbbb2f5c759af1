#pragma once
// Procedural meshes for the built-in scenes, with normals and uvs.
#include <span>

#include "parsed_scene.hpp"

namespace tsr::sg::shapes {

parsed::Primitive sphere(const Vec3& center, float radius, int rings);
parsed::Primitive box(const Vec3& halfExtent);
// A torus around the y axis; a `sweep` below 2 pi leaves an open bend from
// +x towards +z (a pipe elbow), its ends' circles in the planes z = 0 and
// x = 0 when the sweep is a quarter turn.
parsed::Primitive torus(float majorRadius, float minorRadius, int majorSegments, int minorSegments,
                        float sweep = 6.2831853f);
// A surface of revolution around the y axis: `profile` holds (radius, y)
// points in order, each step one band, faced to the outside when the profile
// runs bottom to top on the outside (e.g. (0,0) (r,0) (r,h) (0,h) is a closed
// cylinder). Bands are flat along the profile, smooth around it.
parsed::Primitive lathe(std::span<const Vec2> profile, int segments);
// The triangles lathe() makes, without making them.
std::size_t latheTriangles(std::span<const Vec2> profile, int segments);
// Appends a planar quad (corners in order) as two triangles.
void appendQuad(parsed::Primitive& mesh, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

}  // namespace tsr::sg::shapes
