#pragma once
// EXT_meshopt_compression: buffer views whose bytes are meshoptimizer's
// vertex or index codec over a compressed source, decoded on import with
// Debian's libmeshoptimizer. tinygltf (without the extension) would read
// the views' uncompressed "fallback" buffer, which a GLB leaves without
// bytes; so the document it reads points each compressed view at its
// compressed bytes and has no fallback buffers (takeMeshoptViews), and the
// loader decodes the views into buffers of their own afterwards
// (decodeMeshoptViews). Every size is checked before a byte is written.
#include <cstdint>
#include <string>
#include <vector>

#include <tiny_gltf.h>
#include <nlohmann/json.hpp>

namespace tsr::sg::gltf {

inline constexpr const char* kMeshoptExtension = "EXT_meshopt_compression";

struct MeshoptView {
  std::size_t view = 0;             // the bufferView
  std::uint64_t count = 0;          // elements (vertices or indices)
  std::uint64_t stride = 0;         // bytes an element
  std::string mode, filter;         // ATTRIBUTES | TRIANGLES | INDICES; NONE | OCTAHEDRAL | QUATERNION | EXPONENTIAL
  std::uint64_t declaredBytes = 0;  // the uncompressed view's byteLength
};

// Rewrites `doc` as described above and returns what each compressed view
// decodes to. Throws ImportError for a view that still needs a fallback.
std::vector<MeshoptView> takeMeshoptViews(nlohmann::json& doc, const std::string& source);

// Decodes each view into a new buffer of `model` and points the view at it.
// A decoded view larger than maxBytes, or all of them together larger than
// four times it, is refused.
void decodeMeshoptViews(tinygltf::Model& model, const std::vector<MeshoptView>& views, std::uint64_t maxBytes,
                        const std::string& source);

}  // namespace tsr::sg::gltf
