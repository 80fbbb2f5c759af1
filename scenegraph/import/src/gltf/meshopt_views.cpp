#include "gltf/meshopt_views.hpp"

#include <algorithm>

#include <meshoptimizer.h>

#include "tsr/sg/import/importer.hpp"

namespace tsr::sg::gltf {
namespace {

using nlohmann::json;

const json* extensionOf(const json& object) {
  if (!object.is_object() || !object.contains("extensions") || !object["extensions"].is_object()) return nullptr;
  const json& e = object["extensions"];
  return e.contains(kMeshoptExtension) && e[kMeshoptExtension].is_object() ? &e[kMeshoptExtension] : nullptr;
}

std::uint64_t unsignedField(const json& object, const char* key, std::uint64_t fallback, const std::string& what,
                            const std::string& source) {
  if (!object.contains(key)) return fallback;
  if (!object[key].is_number_unsigned())
    throw ImportError(source, what + "." + key + " must be a non-negative integer");
  return object[key].get<std::uint64_t>();
}

std::string stringField(const json& object, const char* key, const char* fallback, const std::string& what,
                        const std::string& source) {
  if (!object.contains(key)) return fallback;
  if (!object[key].is_string()) throw ImportError(source, what + "." + key + " must be a string");
  return object[key].get<std::string>();
}

}  // namespace

std::vector<MeshoptView> takeMeshoptViews(json& doc, const std::string& source) {
  std::vector<MeshoptView> out;
  if (!doc.contains("bufferViews")) return out;
  json& views = doc["bufferViews"];
  if (!doc.contains("buffers")) doc["buffers"] = json::array();
  json& buffers = doc["buffers"];
  // Fallback buffers: where the extension says the uncompressed bytes would
  // be, for readers without it; a GLB gives them no bytes, and none are read.
  std::vector<bool> fallback(buffers.size(), false);
  for (std::size_t b = 0; b < buffers.size(); ++b)
    if (const json* e = extensionOf(buffers[b]))
      fallback[b] = e->contains("fallback") && (*e)["fallback"].is_boolean() && (*e)["fallback"].get<bool>();
  for (std::size_t v = 0; v < views.size(); ++v) {
    json& view = views[v];
    const std::string what = "bufferViews[" + std::to_string(v) + "]." + kMeshoptExtension;
    const json* found = extensionOf(view);
    if (!found) continue;
    const json e = *found;
    MeshoptView m;
    m.view = v;
    m.count = unsignedField(e, "count", 0, what, source);
    m.stride = unsignedField(e, "byteStride", 0, what, source);
    m.mode = stringField(e, "mode", "", what, source);
    m.filter = stringField(e, "filter", "NONE", what, source);
    m.declaredBytes = unsignedField(view, "byteLength", 0, "bufferViews[" + std::to_string(v) + "]", source);
    if (!e.contains("buffer") || !e.contains("byteLength"))
      throw ImportError(source, what + " needs buffer and byteLength");
    view["buffer"] = unsignedField(e, "buffer", 0, what, source);
    view["byteOffset"] = unsignedField(e, "byteOffset", 0, what, source);
    view["byteLength"] = unsignedField(e, "byteLength", 0, what, source);
    view.erase("byteStride");
    view["extensions"].erase(kMeshoptExtension);
    out.push_back(m);
  }
  // Take the fallback buffers out, renumbering the views that name others.
  std::vector<std::int64_t> renumbered(buffers.size(), -1);
  json kept = json::array();
  for (std::size_t b = 0; b < buffers.size(); ++b)
    if (!fallback[b]) {
      renumbered[b] = static_cast<std::int64_t>(kept.size());
      kept.push_back(buffers[b]);
    }
  if (kept.size() == buffers.size()) return out;
  for (std::size_t v = 0; v < views.size(); ++v) {
    if (!views[v].contains("buffer") || !views[v]["buffer"].is_number_unsigned()) continue;
    const std::uint64_t b = views[v]["buffer"].get<std::uint64_t>();
    if (b >= buffers.size()) continue;  // tinygltf says so
    if (renumbered[b] < 0)
      throw ImportError(source, "bufferViews[" + std::to_string(v) + "] reads fallback buffer " + std::to_string(b) +
                                    ", which has no bytes (only " + kMeshoptExtension + " views may name it)");
    views[v]["buffer"] = renumbered[b];
  }
  buffers = std::move(kept);
  return out;
}

void decodeMeshoptViews(tinygltf::Model& model, const std::vector<MeshoptView>& views, std::uint64_t maxBytes,
                        const std::string& source) {
  // Views may share compressed bytes, and one stream expands up to 64-fold:
  // all of them together decode into at most four times the file limit.
  std::uint64_t left = 4 * maxBytes;
  for (const MeshoptView& m : views) {
    const std::string what = "bufferViews[" + std::to_string(m.view) + "] (" + kMeshoptExtension + ")";
    auto fail = [&](const std::string& reason) { throw ImportError(source, what + ": " + reason); };
    tinygltf::BufferView& view = model.bufferViews.at(m.view);
    if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model.buffers.size())
      fail("names buffer " + std::to_string(view.buffer) + ", which does not exist");
    const std::vector<unsigned char>& source_bytes = model.buffers[static_cast<std::size_t>(view.buffer)].data;
    if (view.byteOffset > source_bytes.size() || view.byteLength > source_bytes.size() - view.byteOffset)
      fail("its compressed bytes run past buffer " + std::to_string(view.buffer));
    const bool attributes = m.mode == "ATTRIBUTES", triangles = m.mode == "TRIANGLES", indices = m.mode == "INDICES";
    if (!attributes && !triangles && !indices) fail("mode '" + m.mode + "' is none of ATTRIBUTES, TRIANGLES, INDICES");
    if (attributes ? (m.stride == 0 || m.stride > 256 || m.stride % 4 != 0) : (m.stride != 2 && m.stride != 4))
      fail("byteStride " + std::to_string(m.stride) + " does not fit mode " + m.mode);
    if (triangles && m.count % 3 != 0) fail("TRIANGLES needs a count divisible by 3, not " + std::to_string(m.count));
    // The uncompressed view's byteLength (within its fallback buffer's, which
    // the file limit bounds) is what the elements may fill.
    if (m.count > std::min(maxBytes, m.declaredBytes) / m.stride)
      fail(std::to_string(m.count) + " elements of " + std::to_string(m.stride) + " bytes do not fit the view's " +
           std::to_string(m.declaredBytes) + " bytes (at most " + std::to_string(maxBytes) + ")");
    if (m.count * m.stride > left)
      fail("the compressed views decode into more than " + std::to_string(4 * maxBytes) +
           " bytes together (four times the file limit)");
    left -= m.count * m.stride;
    std::vector<unsigned char> decoded(static_cast<std::size_t>(m.count * m.stride));
    const unsigned char* compressed = source_bytes.data() + view.byteOffset;
    const int rc =
        attributes  ? meshopt_decodeVertexBuffer(decoded.data(), m.count, m.stride, compressed, view.byteLength)
        : triangles ? meshopt_decodeIndexBuffer(decoded.data(), m.count, m.stride, compressed, view.byteLength)
                    : meshopt_decodeIndexSequence(decoded.data(), m.count, m.stride, compressed, view.byteLength);
    if (rc != 0) fail("the compressed bytes do not decode (meshoptimizer error " + std::to_string(rc) + ")");
    if (m.filter != "NONE" && !attributes) fail("filter " + m.filter + " applies to ATTRIBUTES only");
    if (m.filter == "OCTAHEDRAL") {
      if (m.stride != 4 && m.stride != 8) fail("OCTAHEDRAL needs byteStride 4 or 8");
      meshopt_decodeFilterOct(decoded.data(), m.count, m.stride);
    } else if (m.filter == "QUATERNION") {
      if (m.stride != 8) fail("QUATERNION needs byteStride 8");
      meshopt_decodeFilterQuat(decoded.data(), m.count, m.stride);
    } else if (m.filter == "EXPONENTIAL") {
      meshopt_decodeFilterExp(decoded.data(), m.count, m.stride);
    } else if (m.filter != "NONE") {
      fail("filter '" + m.filter + "' is none of NONE, OCTAHEDRAL, QUATERNION, EXPONENTIAL");
    }
    tinygltf::Buffer buffer;
    buffer.data = std::move(decoded);
    model.buffers.push_back(std::move(buffer));
    view.buffer = static_cast<int>(model.buffers.size() - 1);
    view.byteOffset = 0;
    view.byteLength = static_cast<std::size_t>(m.count * m.stride);
    // Decoded vertices lie `stride` apart; indices are packed.
    view.byteStride = attributes ? static_cast<std::size_t>(m.stride) : 0;
  }
}

}  // namespace tsr::sg::gltf
