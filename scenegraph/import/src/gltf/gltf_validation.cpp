#include "gltf/gltf_validation.hpp"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <functional>
#include <map>

#include "tsr/sg/import/import_error.hpp"

namespace tsr::sg::gltf {
namespace {

using nlohmann::json;

constexpr std::uint32_t kMaxNodeDepth = 4096;

const char* const kSupportedExtensions[] = {
    "KHR_lights_punctual",  "KHR_materials_emissive_strength", "KHR_materials_transmission", "KHR_materials_ior",
    "KHR_materials_volume", "KHR_texture_transform",           "TSR_materials_volume",       "TSR_scene_medium",
    "TSR_camera_lens",      "KHR_draco_mesh_compression",      "EXT_meshopt_compression",    "KHR_mesh_quantization"};

// A small schema language: each check looks at one value at a JSON path and
// throws with that path in the message.
class TypeChecker {
 public:
  explicit TypeChecker(const std::string& source) : source_(source) {}

  using Check = std::function<void(const json&, const std::string&)>;

  [[noreturn]] void fail(const std::string& path, const std::string& what) const {
    throw ImportError(source_, path + " must be " + what);
  }

  Check index() const {
    return [this](const json& v, const std::string& p) {
      if (!v.is_number_integer() || v.get<std::int64_t>() < 0) fail(p, "a non-negative integer index");
    };
  }
  Check integer() const {
    return [this](const json& v, const std::string& p) {
      if (!v.is_number_integer()) fail(p, "an integer");
    };
  }
  Check number() const {
    return [this](const json& v, const std::string& p) {
      if (!v.is_number()) fail(p, "a number");
    };
  }
  Check string() const {
    return [this](const json& v, const std::string& p) {
      if (!v.is_string()) fail(p, "a string");
    };
  }
  Check boolean() const {
    return [this](const json& v, const std::string& p) {
      if (!v.is_boolean()) fail(p, "true or false");
    };
  }
  // An array of `n` numbers (any length when n is 0).
  Check numbers(std::size_t n = 0) const {
    return [this, n](const json& v, const std::string& p) {
      const std::string what = n ? "an array of " + std::to_string(n) + " numbers" : "an array of numbers";
      if (!v.is_array() || (n && v.size() != n)) fail(p, what);
      for (const json& e : v)
        if (!e.is_number()) fail(p, what);
    };
  }
  Check arrayOf(Check element) const {
    return [this, element = std::move(element)](const json& v, const std::string& p) {
      if (!v.is_array()) fail(p, "an array");
      for (std::size_t i = 0; i < v.size(); ++i) element(v[i], p + "[" + std::to_string(i) + "]");
    };
  }
  Check object(std::map<std::string, Check> properties) const {
    return [this, properties = std::move(properties)](const json& v, const std::string& p) {
      if (!v.is_object()) fail(p, "an object");
      for (const auto& [key, check] : properties)
        if (auto it = v.find(key); it != v.end()) check(*it, p + "." + key);
    };
  }
  Check mapOf(Check value) const {
    return [this, value = std::move(value)](const json& v, const std::string& p) {
      if (!v.is_object()) fail(p, "an object");
      for (const auto& [key, item] : v.items()) value(item, p + "." + key);
    };
  }

 private:
  std::string source_;
};

TypeChecker::Check documentSchema(const TypeChecker& t) {
  const auto textureTransform =
      t.object({{"offset", t.numbers(2)}, {"rotation", t.number()}, {"scale", t.numbers(2)}, {"texCoord", t.index()}});
  const auto textureInfo = t.object({{"index", t.index()},
                                     {"texCoord", t.index()},
                                     {"scale", t.number()},
                                     {"strength", t.number()},
                                     {"extensions", t.object({{"KHR_texture_transform", textureTransform}})}});
  // Tessera's volume extension (docs/volumes.md).
  const auto tesseraVolume = t.object({{"emission", t.numbers(3)},
                                       {"absorption", t.numbers(3)},
                                       {"scattering", t.numbers(3)},
                                       {"phaseG", t.number()},
                                       {"absorptionTexture", textureInfo},
                                       {"scatteringTexture", textureInfo},
                                       {"emissionTexture", textureInfo},
                                       {"textureSlices", t.number()}});
  const auto material = t.object({
      {"name", t.string()},
      {"pbrMetallicRoughness", t.object({{"baseColorFactor", t.numbers(4)},
                                         {"baseColorTexture", textureInfo},
                                         {"metallicFactor", t.number()},
                                         {"roughnessFactor", t.number()},
                                         {"metallicRoughnessTexture", textureInfo}})},
      {"normalTexture", textureInfo},
      {"occlusionTexture", textureInfo},
      {"emissiveTexture", textureInfo},
      {"emissiveFactor", t.numbers(3)},
      {"alphaMode", t.string()},
      {"alphaCutoff", t.number()},
      {"doubleSided", t.boolean()},
      {"extensions", t.object({{"KHR_materials_emissive_strength", t.object({{"emissiveStrength", t.number()}})},
                               {"KHR_materials_transmission",
                                t.object({{"transmissionFactor", t.number()}, {"transmissionTexture", textureInfo}})},
                               {"KHR_materials_ior", t.object({{"ior", t.number()}})},
                               {"KHR_materials_volume", t.object({{"thicknessFactor", t.number()},
                                                                  {"thicknessTexture", textureInfo},
                                                                  {"attenuationDistance", t.number()},
                                                                  {"attenuationColor", t.numbers(3)}})},
                               {"TSR_materials_volume", tesseraVolume}})},
  });
  const auto primitive = t.object({{"attributes", t.mapOf(t.index())},
                                   {"indices", t.index()},
                                   {"material", t.index()},
                                   {"mode", t.integer()},
                                   {"targets", t.arrayOf(t.mapOf(t.index()))}});
  const auto node = t.object({{"name", t.string()},
                              {"camera", t.index()},
                              {"children", t.arrayOf(t.index())},
                              {"skin", t.index()},
                              {"matrix", t.numbers(16)},
                              {"mesh", t.index()},
                              {"rotation", t.numbers(4)},
                              {"scale", t.numbers(3)},
                              {"translation", t.numbers(3)},
                              {"weights", t.numbers()},
                              {"extensions", t.object({{"KHR_lights_punctual", t.object({{"light", t.index()}})}})}});
  const auto accessor = t.object({
      {"bufferView", t.index()},
      {"byteOffset", t.index()},
      {"componentType", t.integer()},
      {"normalized", t.boolean()},
      {"count", t.index()},
      {"type", t.string()},
      {"min", t.numbers()},
      {"max", t.numbers()},
      {"sparse",
       t.object({{"count", t.index()},
                 {"indices",
                  t.object({{"bufferView", t.index()}, {"byteOffset", t.index()}, {"componentType", t.integer()}})},
                 {"values", t.object({{"bufferView", t.index()}, {"byteOffset", t.index()}})}})},
  });
  const auto light = t.object({{"type", t.string()},
                               {"color", t.numbers(3)},
                               {"intensity", t.number()},
                               {"range", t.number()},
                               {"spot", t.object({{"innerConeAngle", t.number()}, {"outerConeAngle", t.number()}})}});
  return t.object({
      {"asset", t.object({{"version", t.string()}, {"minVersion", t.string()}})},
      {"scene", t.index()},
      {"scenes", t.arrayOf(t.object({{"nodes", t.arrayOf(t.index())},
                                     {"extensions", t.object({{"TSR_scene_medium", tesseraVolume}})}}))},
      {"nodes", t.arrayOf(node)},
      {"meshes", t.arrayOf(t.object({{"primitives", t.arrayOf(primitive)}, {"weights", t.numbers()}}))},
      {"materials", t.arrayOf(material)},
      {"accessors", t.arrayOf(accessor)},
      {"bufferViews", t.arrayOf(t.object({{"buffer", t.index()},
                                          {"byteOffset", t.index()},
                                          {"byteLength", t.index()},
                                          {"byteStride", t.index()},
                                          {"target", t.integer()}}))},
      {"buffers", t.arrayOf(t.object({{"byteLength", t.index()}, {"uri", t.string()}}))},
      {"images", t.arrayOf(t.object({{"uri", t.string()}, {"mimeType", t.string()}, {"bufferView", t.index()}}))},
      {"textures", t.arrayOf(t.object({{"sampler", t.index()}, {"source", t.index()}}))},
      {"samplers",
       t.arrayOf(t.object(
           {{"magFilter", t.integer()}, {"minFilter", t.integer()}, {"wrapS", t.integer()}, {"wrapT", t.integer()}}))},
      {"cameras",
       t.arrayOf(t.object(
           {{"type", t.string()},
            {"perspective",
             t.object(
                 {{"yfov", t.number()}, {"znear", t.number()}, {"zfar", t.number()}, {"aspectRatio", t.number()}})},
            {"orthographic",
             t.object({{"xmag", t.number()}, {"ymag", t.number()}, {"znear", t.number()}, {"zfar", t.number()}})},
            {"extensions", t.object({{"TSR_camera_lens",
                                      t.object({{"apertureRadius", t.number()}, {"focusDistance", t.number()}})}})}}))},
      {"animations",
       t.arrayOf(t.object(
           {{"channels", t.arrayOf(t.object({{"sampler", t.index()},
                                             {"target", t.object({{"node", t.index()}, {"path", t.string()}})}}))},
            {"samplers",
             t.arrayOf(t.object({{"input", t.index()}, {"output", t.index()}, {"interpolation", t.string()}}))}}))},
      {"extensionsUsed", t.arrayOf(t.string())},
      {"extensionsRequired", t.arrayOf(t.string())},
      {"extensions", t.object({{"KHR_lights_punctual", t.object({{"lights", t.arrayOf(light)}})}})},
  });
}

}  // namespace

bool isSupportedExtension(const std::string& name) {
  return std::find(std::begin(kSupportedExtensions), std::end(kSupportedExtensions), name) !=
         std::end(kSupportedExtensions);
}

void checkJsonTypes(const json& doc, const std::string& source) {
  TypeChecker checker(source);
  if (!doc.is_object()) checker.fail("the document", "a JSON object");
  documentSchema(checker)(doc, "glTF");
}

namespace {

std::string percentDecoded(const std::string& uri) {
  std::string out;
  for (std::size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
      out += static_cast<char>(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

// Why a (decoded) relative uri may not be opened, or empty when it may.
std::string uriProblem(const std::string& uri) {
  const std::size_t colon = uri.find(':');
  const std::size_t slash = uri.find_first_of("/\\");
  if (colon != std::string::npos && (slash == std::string::npos || colon < slash))
    return "has a scheme; only files beside the glTF and data: uris are read";
  if (!uri.empty() && (uri[0] == '/' || uri[0] == '\\'))
    return "is an absolute path; only files beside the glTF are read";
  if (uri.find('\0') != std::string::npos) return "holds a NUL byte";
  int depth = 0;
  std::size_t start = 0;
  while (start <= uri.size()) {
    std::size_t end = uri.find_first_of("/\\", start);
    if (end == std::string::npos) end = uri.size();
    const std::string part = uri.substr(start, end - start);
    if (part == "..") {
      if (--depth < 0) return "leaves the glTF file's folder";
    } else if (!part.empty() && part != ".") {
      ++depth;
    }
    start = end + 1;
  }
  return {};
}

}  // namespace

void checkUris(const json& doc, const std::string& source) {
  for (const char* array : {"buffers", "images"}) {
    if (!doc.contains(array)) continue;
    const json& items = doc.at(array);
    for (std::size_t i = 0; i < items.size(); ++i) {
      if (!items[i].contains("uri")) continue;
      const std::string& uri = items[i].at("uri").get_ref<const std::string&>();
      if (uri.rfind("data:", 0) == 0) continue;
      const std::string problem = uriProblem(percentDecoded(uri));
      if (!problem.empty())
        throw ImportError(source, std::string(array, std::strlen(array) - 1) + " " + std::to_string(i) + " uri '" +
                                      uri + "' " + problem + "; refused, not read");
    }
  }
}

void checkDeclaredSizes(const json& doc, std::uint64_t maxFileBytes, const std::string& source) {
  if (!doc.contains("buffers")) return;
  const json& buffers = doc.at("buffers");
  for (std::size_t i = 0; i < buffers.size(); ++i) {
    if (!buffers[i].contains("byteLength")) continue;
    const std::uint64_t declared = buffers[i].at("byteLength").get<std::uint64_t>();
    if (declared > maxFileBytes)
      throw ImportLimitError(source,
                             "buffer " + std::to_string(i) + " declares " + std::to_string(declared) +
                                 " bytes, more than the limit of " + std::to_string(maxFileBytes) + " bytes (" +
                                 std::to_string(maxFileBytes >> 20) + " MiB)",
                             ImportLimitError::Limit::FileBytes);
  }
}

void checkRequiredExtensions(const tinygltf::Model& model, const std::string& source) {
  for (const std::string& ext : model.extensionsRequired)
    if (!isSupportedExtension(ext)) throw ImportError(source, "required extension " + ext + " is not supported");
}

void checkNodeGraph(const tinygltf::Model& model, const std::string& source) {
  const std::size_t n = model.nodes.size();
  std::vector<int> parent(n, -1);
  for (std::size_t i = 0; i < n; ++i)
    for (int c : model.nodes[i].children) {
      if (c < 0 || static_cast<std::size_t>(c) >= n)
        throw ImportError(source, "node " + std::to_string(i) + " has child " + std::to_string(c) + ", but there are " +
                                      std::to_string(n) + " nodes");
      if (static_cast<std::size_t>(c) == i)
        throw ImportError(source, "node " + std::to_string(i) + " is its own child");
      if (parent[static_cast<std::size_t>(c)] != -1)
        throw ImportError(source, "node " + std::to_string(c) + " is a child of two parents (nodes " +
                                      std::to_string(parent[static_cast<std::size_t>(c)]) + " and " +
                                      std::to_string(i) + ")");
      parent[static_cast<std::size_t>(c)] = static_cast<int>(i);
    }
  // With one parent each, a cycle is a chain of parents that never ends at
  // a root; follow each chain at most n steps, remembering finished nodes.
  std::vector<char> done(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t steps = 0;
    std::size_t k = i;
    while (!done[k] && parent[k] != -1) {
      k = static_cast<std::size_t>(parent[k]);
      if (++steps > n)
        throw ImportError(source, "node " + std::to_string(i) + " is its own ancestor (cyclic node graph)");
    }
    for (k = i; !done[k]; k = parent[k] == -1 ? k : static_cast<std::size_t>(parent[k])) {
      done[k] = 1;
      if (parent[k] == -1) break;
    }
  }
  // The importer builds the hierarchy recursively; bound the depth.
  std::vector<std::uint32_t> depth(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    if (depth[i]) continue;
    std::vector<std::size_t> chain;
    std::size_t k = i;
    while (!depth[k]) {
      chain.push_back(k);
      if (parent[k] == -1) break;
      k = static_cast<std::size_t>(parent[k]);
    }
    std::uint32_t d = depth[k] ? depth[k] : 0;
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
      depth[*it] = ++d;
      if (d > kMaxNodeDepth)
        throw ImportError(source, "node " + std::to_string(*it) + " is nested more than " +
                                      std::to_string(kMaxNodeDepth) + " levels deep");
    }
  }
}

}  // namespace tsr::sg::gltf
