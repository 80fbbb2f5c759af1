#pragma once
// KHR_draco_mesh_compression: a primitive whose vertices and triangles are a
// Draco stream in one buffer view, decoded with Debian's libdraco. The
// stream is checked against the document before and after decoding: the
// view lies inside its buffer, the declared accessor counts are within the
// import limits, and what the stream holds matches what the accessors
// declare (the extension requires it), so nothing larger than the document
// says is ever handed on.
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include <tiny_gltf.h>

#include "parsed_scene.hpp"

namespace tsr::sg::gltf {

inline constexpr const char* kDracoExtension = "KHR_draco_mesh_compression";

// The "indices" accessor of each compressed primitive, (mesh, primitive) ->
// accessor or -1. tinygltf as Debian builds it has no Draco and refuses an
// index accessor without a buffer view, so the document it reads has these
// taken out (takeDracoIndices) and the importer decodes the stream itself.
using DracoIndices = std::map<std::pair<std::size_t, std::size_t>, int>;

// Takes "indices" out of the compressed primitives of `doc`, after checking
// the extension's kinds and that its indices fit tinygltf's int. Throws
// ImportError naming the primitive.
DracoIndices takeDracoIndices(nlohmann::json& doc, const std::string& source);

// Fills positions, normals, uvs (TEXCOORD_0), colours (COLOR_0) and indices
// (a triangle list, whatever the primitive's mode) of `out` from the
// stream. indicesAccessor is the primitive's "indices" (-1 when it has
// none), which the loader kept aside. elementsLeft is what the file's
// streams may still hold, vertices and indices, of maxElements; it is
// charged before decoding. Throws ImportError naming `what` and the
// extension.
void decodeDracoPrimitive(const tinygltf::Model& model, const tinygltf::Primitive& primitive, int indicesAccessor,
                          std::uint64_t maxElements, std::uint64_t& elementsLeft, const std::string& source,
                          const std::string& what, parsed::Primitive& out);

}  // namespace tsr::sg::gltf
