#include <charconv>

#include <spdlog/spdlog.h>

#include "builtin_scenes.hpp"
#include "gltf_importer.hpp"
#include "parsed_scene.hpp"
#include "tsr/sg/import/importer.hpp"
#include "tsr/sg/scene.hpp"

namespace tsr::sg {
namespace {

constexpr std::string_view kBuiltinPrefix = "builtin:";
constexpr std::uint64_t kMaxInstances = 10'000'000;

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + std::string(kBuiltinPrefix) + n;
  return out;
}

parsed::Scene parseBuiltin(const std::string& source) {
  const std::string_view name = std::string_view(source).substr(kBuiltinPrefix.size());
  if (name == "cornell") return builtin::cornell();
  if (name == "animated") return builtin::animated();
  constexpr std::string_view instances = "instances:";
  if (name.starts_with(instances)) {
    const std::string_view digits = name.substr(instances.size());
    std::uint64_t n = 0;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), n);
    if (digits.empty() || ec != std::errc() || end != digits.data() + digits.size() || n == 0 || n > kMaxInstances)
      throw ImportError(source, "the instance count must be a whole number from 1 to " + std::to_string(kMaxInstances) +
                                    ", not '" + std::string(digits) + "'");
    return builtin::instances(n);
  }
  throw ImportError(source, "unknown built-in scene; valid names are " + joined(builtinSceneNames()));
}

// Runs a parser with every failure turned into an ImportError, then builds.
template <class Parse>
ImportResult parsedAndBuilt(Scene& scene, const std::string& source, Parse parse) {
  parsed::Scene data;
  try {
    data = parse();
  } catch (const ImportError&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw ImportError(source, "out of memory while reading the scene");
  } catch (const std::exception& e) {
    throw ImportError(source, e.what());
  }
  // Everything is checked: from here on only containers are created.
  ImportResult result = buildScene(scene, data);
  spdlog::debug("imported {}: {} nodes, {} geometries, {} triangles, {} warnings", source, result.counts.nodes,
                result.counts.geometries, result.counts.uniqueTriangles, result.warnings.size());
  return result;
}

}  // namespace

std::vector<std::string> builtinSceneNames() { return {"cornell", "instances:N", "animated"}; }

ImportResult importScene(Scene& scene, const std::string& source, const ImportOptions& options) {
  return parsedAndBuilt(scene, source, [&] {
    return source.starts_with(kBuiltinPrefix) ? parseBuiltin(source) : gltf::parseFile(source, options);
  });
}

ImportResult importGltf(Scene& scene, std::span<const std::uint8_t> bytes, const std::string& source,
                        const std::string& baseDir, const ImportOptions& options) {
  return parsedAndBuilt(scene, source, [&] { return gltf::parseBytes(bytes, source, baseDir, options); });
}

}  // namespace tsr::sg
