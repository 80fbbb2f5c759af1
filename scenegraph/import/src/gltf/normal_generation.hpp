#pragma once
// Normals for primitives that come without them.
#include "parsed_scene.hpp"

namespace tsr::sg {

// Averages the area-weighted normals of the triangles sharing each vertex.
void generateSmoothNormals(parsed::Primitive& p);

}  // namespace tsr::sg
