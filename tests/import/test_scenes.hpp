#pragma once
// The glTF documents the import tests share.
#include "gltf_writer.hpp"

namespace tsr::test {

// Texture pixels the rich scene uses: tex.png (2x2 RGBA, external file)
// and a 2x1 RGB PNG embedded as a data URI.
extern const std::vector<std::uint8_t> kFilePixels;
extern const std::vector<std::uint8_t> kUriPixels;

// Nodes: 0 "parent" (T 10,0,0) with children 1 "childA" (T 0,5,0, mesh 0)
// and 2 "childB" (S 2, mesh 0) and 5 "camera" (T 0,0,10); 3 "matrix" (a
// matrix, mesh 1); 4 "strips" (mesh 2); 6-8 point, spot and directional
// lights. Mesh 0: a unit quad in z=0, interleaved positions+uvs, u16
// indices, no normals. Mesh 1: one triangle, u8 indices, normals, u8
// colours, u16 uvs. Mesh 2: u32 strip, u8 fan, a points primitive and a
// non-indexed triangle with vec3 colours, no material. Writes tex.png.
GltfBuilder richScene(const TempDir& dir);

// One node with a one-triangle mesh: the smallest valid document.
GltfBuilder tinyScene();

}  // namespace tsr::test
