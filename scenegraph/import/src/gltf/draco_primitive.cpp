#include "gltf/draco_primitive.hpp"

#include <climits>
#include <cmath>

#include <draco/compression/decode.h>

#include "gltf/gltf_accessors.hpp"
#include "tsr/sg/import/importer.hpp"

namespace tsr::sg::gltf {
namespace {

std::string str(std::uint64_t v) { return std::to_string(v); }

// A Draco attribute read as floats (integers as the stream declares them):
// its own components a vertex, the rest of Vec as (0, 0, 0, 1). An accessor
// that says `normalized` over integers the stream does not mark normalized
// gets glTF's mapping here. False when a value cannot be converted or is
// not finite (NaN or infinity), as the accessors' reader refuses them.
template <class Vec>
bool attributeValues(const draco::Mesh& mesh, const draco::PointAttribute& a, bool accessorNormalized,
                     std::vector<Vec>& out) {
  const int components = a.num_components();
  // glTF's name for the stream's integer type (0: not one glTF normalizes).
  const int componentType = !accessorNormalized || a.normalized() ? 0
                            : a.data_type() == draco::DT_UINT8    ? TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE
                            : a.data_type() == draco::DT_INT8     ? TINYGLTF_COMPONENT_TYPE_BYTE
                            : a.data_type() == draco::DT_UINT16   ? TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT
                            : a.data_type() == draco::DT_INT16    ? TINYGLTF_COMPONENT_TYPE_SHORT
                                                                  : 0;
  out.assign(mesh.num_points(), Vec(0.0f));
  for (draco::PointIndex i(0); i < mesh.num_points(); ++i) {
    float v[4] = {0.0f, 0.0f, 0.0f, 1.0f};
    if (!a.ConvertValue<float>(a.mapped_index(i), static_cast<std::int8_t>(components), v)) return false;
    if (componentType)
      for (int c = 0; c < components; ++c) v[c] = normalizedInteger(v[c], componentType);
    for (int c = 0; c < Vec::length(); ++c) {
      if (!std::isfinite(v[c])) return false;
      out[i.value()][c] = v[c];
    }
  }
  return true;
}

}  // namespace

DracoIndices takeDracoIndices(nlohmann::json& doc, const std::string& source) {
  DracoIndices out;
  if (!doc.contains("meshes")) return out;
  // tinygltf keeps integers as int: larger ones would name another element.
  auto index = [&](const nlohmann::json& v, const std::string& what) {
    if (!v.is_number_unsigned() || v.get<std::uint64_t>() > std::uint64_t{INT_MAX})
      throw ImportError(source, what + " must be an index from 0 to " + std::to_string(INT_MAX));
    return v.get<int>();
  };
  nlohmann::json& meshes = doc["meshes"];
  for (std::size_t mi = 0; mi < meshes.size(); ++mi) {
    if (!meshes[mi].contains("primitives")) continue;
    nlohmann::json& primitives = meshes[mi]["primitives"];
    for (std::size_t pi = 0; pi < primitives.size(); ++pi) {
      nlohmann::json& p = primitives[pi];
      if (!p.contains("extensions") || !p["extensions"].is_object() ||
          !p["extensions"].contains("KHR_draco_mesh_compression"))
        continue;
      const std::string what =
          "meshes[" + std::to_string(mi) + "].primitives[" + std::to_string(pi) + "].KHR_draco_mesh_compression";
      const nlohmann::json& e = p["extensions"]["KHR_draco_mesh_compression"];
      if (!e.is_object() || !e.contains("bufferView") || !e.contains("attributes") || !e["attributes"].is_object())
        throw ImportError(source, what + " needs a bufferView and an attributes object");
      index(e["bufferView"], what + ".bufferView");
      for (const auto& [name, id] : e["attributes"].items()) index(id, what + ".attributes." + name);
      out[{mi, pi}] = p.contains("indices") ? index(p["indices"], what + " primitive's indices") : -1;
      p.erase("indices");
    }
  }
  return out;
}

void decodeDracoPrimitive(const tinygltf::Model& model, const tinygltf::Primitive& primitive, int indicesAccessor,
                          std::uint64_t maxElements, std::uint64_t& elementsLeft, const std::string& source,
                          const std::string& what, parsed::Primitive& out) {
  const std::string where = what + " (" + kDracoExtension + ")";
  auto fail = [&](const std::string& reason) { throw ImportError(source, where + ": " + reason); };
  // takeDracoIndices checked the extension's kinds and kept its indices to int.
  const auto found = primitive.extensions.find(kDracoExtension);
  if (found == primitive.extensions.end()) fail("is missing after loading");
  const tinygltf::Value& ext = found->second;
  const int viewIndex = ext.Get("bufferView").Get<int>();
  if (viewIndex < 0 || static_cast<std::size_t>(viewIndex) >= model.bufferViews.size())
    fail("bufferView " + std::to_string(viewIndex) + " does not exist (there are " + str(model.bufferViews.size()) +
         ")");
  const tinygltf::BufferView& view = model.bufferViews[static_cast<std::size_t>(viewIndex)];
  if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model.buffers.size())
    fail("bufferView " + std::to_string(viewIndex) + " names buffer " + std::to_string(view.buffer) +
         ", which does not exist");
  const std::vector<unsigned char>& buffer = model.buffers[static_cast<std::size_t>(view.buffer)].data;
  if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset)
    fail("bufferView " + std::to_string(viewIndex) + " (bytes " + str(view.byteOffset) + " to " +
         str(view.byteOffset + view.byteLength) + ") runs past its buffer of " + str(buffer.size()) + " bytes");

  // What the accessors declare, within the limits, before anything is decoded.
  auto declared = [&](int accessor, const std::string& name) -> std::uint64_t {
    if (accessor < 0 || static_cast<std::size_t>(accessor) >= model.accessors.size())
      fail(name + " names accessor " + std::to_string(accessor) + ", which does not exist");
    const std::uint64_t count = model.accessors[static_cast<std::size_t>(accessor)].count;
    if (count > maxElements)
      fail(name + " declares " + str(count) + " elements, more than the limit of " + str(maxElements));
    return count;
  };
  const auto position = primitive.attributes.find("POSITION");
  if (position == primitive.attributes.end()) fail("has no POSITION attribute");
  const std::uint64_t points = declared(position->second, "POSITION");
  const std::uint64_t indexCount = indicesAccessor >= 0 ? declared(indicesAccessor, "indices") : 0;
  // Primitives may share a stream: all of them together within the limit.
  if (points + indexCount > elementsLeft)
    fail("the Draco streams hold more than " + str(maxElements) + " vertices and indices together");
  elementsLeft -= points + indexCount;

  draco::DecoderBuffer stream;
  stream.Init(reinterpret_cast<const char*>(buffer.data() + view.byteOffset), view.byteLength);
  const auto type = draco::Decoder::GetEncodedGeometryType(&stream);
  if (!type.ok() || type.value() != draco::TRIANGULAR_MESH)
    fail("bufferView " + std::to_string(viewIndex) + " is not a Draco triangle mesh" +
         (type.ok() ? std::string() : ": " + type.status().error_msg_string()));
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&stream);
  if (!decoded.ok()) fail("the Draco stream does not decode: " + decoded.status().error_msg_string());
  const draco::Mesh& mesh = *decoded.value();
  if (mesh.num_points() != points)
    fail("the stream holds " + str(mesh.num_points()) + " vertices, POSITION declares " + str(points));
  if (indicesAccessor >= 0 && std::uint64_t{mesh.num_faces()} * 3 != indexCount)
    fail("the stream holds " + str(mesh.num_faces()) + " triangles (" + str(std::uint64_t{mesh.num_faces()} * 3) +
         " indices), the indices accessor declares " + str(indexCount));

  // The glTF attributes this importer reads, each from the Draco attribute
  // the extension maps it to.
  const tinygltf::Value& ids = ext.Get("attributes");
  auto dracoAttribute = [&](const std::string& name, int minComponents,
                            int maxComponents) -> const draco::PointAttribute* {
    if (!ids.Has(name)) return nullptr;
    const int id = ids.Get(name).Get<int>();
    const draco::PointAttribute* a = id < 0 ? nullptr : mesh.GetAttributeByUniqueId(static_cast<std::uint32_t>(id));
    if (!a) fail("attribute " + name + " names Draco attribute " + std::to_string(id) + ", which the stream lacks");
    if (a->num_components() < minComponents || a->num_components() > maxComponents)
      fail("attribute " + name + " has " + std::to_string(a->num_components()) + " components");
    return a;
  };
  auto read = [&](const std::string& name, const draco::PointAttribute* a, auto& values) {
    const auto accessor = primitive.attributes.find(name);
    const bool normalized = accessor != primitive.attributes.end() && accessor->second >= 0 &&
                            static_cast<std::size_t>(accessor->second) < model.accessors.size() &&
                            model.accessors[static_cast<std::size_t>(accessor->second)].normalized;
    if (a && !attributeValues(mesh, *a, normalized, values))
      fail("attribute " + name + " holds values that are not finite numbers");
  };
  const draco::PointAttribute* positions = dracoAttribute("POSITION", 3, 3);
  if (!positions) fail("attributes has no POSITION");
  read("POSITION", positions, out.positions);
  read("NORMAL", dracoAttribute("NORMAL", 3, 3), out.normals);
  read("TEXCOORD_0", dracoAttribute("TEXCOORD_0", 2, 2), out.uvs);
  read("COLOR_0", dracoAttribute("COLOR_0", 3, 4), out.colors);
  out.indices.resize(std::size_t{mesh.num_faces()} * 3);
  for (draco::FaceIndex f(0); f < mesh.num_faces(); ++f)
    for (int c = 0; c < 3; ++c) out.indices[3 * std::size_t{f.value()} + c] = mesh.face(f)[c].value();
}

}  // namespace tsr::sg::gltf
