#include <charconv>
#include <chrono>
#include <filesystem>
#include <optional>

#include <spdlog/spdlog.h>

#include "builtin/builtin_scenes.hpp"
#include "cache/scene_cache.hpp"
#include "cache/stamp_index.hpp"
#include "gltf/gltf_importer.hpp"
#include "gltf/gltf_loader.hpp"
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

// The whole number `digits` of a built-in name, from `min` to `max`.
std::uint64_t count(const std::string& source, std::string_view digits, std::uint64_t min, std::uint64_t max,
                    const std::string& what) {
  std::uint64_t n = 0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), n);
  if (digits.empty() || ec != std::errc() || end != digits.data() + digits.size() || n < min || n > max)
    throw ImportError(source, what + " must be a whole number from " + std::to_string(min) + " to " +
                                  std::to_string(max) + ", not '" + std::string(digits) + "'");
  return n;
}

// A built-in scene's name, read once: which generator and its count (0
// for those without one). Unknown names and bad counts are ImportErrors.
struct BuiltinName {
  std::string_view kind;  // "cornell", "instances:", "plant:", ...
  std::uint64_t count = 0;
  // As the cache keys it: the count without leading zeros ("plant:020000"
  // is "plant:20000").
  std::string canonical() const {
    return std::string(kBuiltinPrefix) + std::string(kind) + (kind.ends_with(':') ? std::to_string(count) : "");
  }
};

BuiltinName readBuiltinName(const std::string& source) {
  const std::string_view name = std::string_view(source).substr(kBuiltinPrefix.size());
  for (std::string_view fixed : {"cornell", "cornell-fog", "animated"})
    if (name == fixed) return {fixed};
  constexpr std::string_view instances = "instances:", plant = "plant:";
  if (name.starts_with(instances))
    return {instances, count(source, name.substr(instances.size()), 1, kMaxInstances, "the instance count")};
  if (name.starts_with(plant))
    return {plant, count(source, name.substr(plant.size()), builtin::kPlantMinTriangles, builtin::kPlantMaxTriangles,
                         "the triangle budget")};
  throw ImportError(source, "unknown built-in scene; valid names are " + joined(builtinSceneNames()));
}

parsed::Scene makeBuiltin(const BuiltinName& b) {
  if (b.kind == "cornell") return builtin::cornell();
  if (b.kind == "cornell-fog") return builtin::cornellFog();
  if (b.kind == "animated") return builtin::animated();
  if (b.kind == "instances:") return builtin::instances(b.count);
  return builtin::plant(b.count);
}

parsed::Scene parseBuiltin(const std::string& source) { return makeBuiltin(readBuiltinName(source)); }

// A file through the converted-scene cache (ImportOptions::cacheDir): the
// kept conversion when its entry checks out, else the file parsed and kept.
// A built-in scene is kept too (the 300 M-triangle plant takes minutes to
// make and seconds to read back), keyed by its name: what the generators
// make for a name is pinned to the importer version by a test
// (BuiltinScenes.ImporterVersionPinsWhatTheyMake).
parsed::Scene parseCached(const std::string& source, const ImportOptions& options, std::string& note) {
  const bool builtin = source.starts_with(kBuiltinPrefix);
  // A file unchanged since it was last hashed is known by its stamp
  // (stamp_index.hpp); else its bytes are mapped while they are hashed (and
  // parsed on a miss), not while the kept conversion is read: a hit keeps
  // the entry mapped as long as the scene's arrays live in it, never the
  // source.
  const std::optional<cache::FileStamp> stamp = builtin ? std::nullopt : cache::FileStamp::of(source);
  const std::optional<std::string> recorded =
      stamp ? cache::recordedKey(options.cacheDir, source, options, *stamp) : std::nullopt;
  const std::optional<BuiltinName> builtinName =
      builtin ? std::optional<BuiltinName>(readBuiltinName(source)) : std::nullopt;
  const std::string key = builtin    ? cache::builtinKey(builtinName->canonical())
                          : recorded ? *recorded
                                     : cache::key(gltf::mapSource(source, options).bytes(), options);
  const std::filesystem::path entry = cache::entryPath(options.cacheDir, key);
  std::string why;
  if (std::optional<parsed::Scene> kept = cache::load(entry, key, why)) {
    spdlog::info("{}: converted scene read from {}", source, entry.string());
    if (stamp && !recorded) cache::recordKey(options.cacheDir, source, options, *stamp, key);
    note = "hit";
    return std::move(*kept);
  }
  const bool refused = why != "no entry";
  if (refused)
    spdlog::warn("{}: the converted scene in {} is refused ({}); converting again", source, entry.string(), why);
  const MappedFile file = builtin ? MappedFile() : gltf::mapSource(source, options);
  parsed::Scene scene =
      builtin ? makeBuiltin(*builtinName)
              : gltf::parseBytes(file.bytes(), source, std::filesystem::path(source).parent_path().string(), options);
  std::string failed;
  bool kept = false;
  if (scene.readOtherFiles)
    note = "not stored (the file names external buffers or images)";
  else if (!builtin && cache::key(file.bytes(), options) != key)
    // Replaced between the two mappings: its conversion must not be kept
    // under the key of the bytes hashed first.
    note = "not stored (the file changed while it was read)";
  else if (!cache::store(entry, key, scene, failed))
    note = "not stored (" + failed + ")";
  else {
    note = refused ? "rebuilt (" + why + ")" : "stored";
    kept = true;
  }
  if (kept && stamp) cache::recordKey(options.cacheDir, source, options, *stamp, key);
  spdlog::info("{}: converted scene {} in {}", source, note, options.cacheDir);
  return scene;
}

// Runs a parser with every failure turned into an ImportError, then builds.
template <class Parse>
ImportResult parsedAndBuilt(Scene& scene, const std::string& source, Parse parse) {
  const auto start = std::chrono::steady_clock::now();
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
  ImportResult result = buildScene(scene, std::move(data));
  const std::chrono::duration<double> took = std::chrono::steady_clock::now() - start;
  spdlog::debug("imported {} in {:.2f} s: {} nodes, {} geometries, {} triangles, {} warnings", source, took.count(),
                result.counts.nodes, result.counts.geometries, result.counts.uniqueTriangles, result.warnings.size());
  return result;
}

}  // namespace

std::vector<std::string> builtinSceneNames() {
  return {"cornell", "cornell-fog", "instances:N", "animated", "plant:TRIANGLES"};
}

ImportResult importScene(Scene& scene, const std::string& source, const ImportOptions& options) {
  const bool cached = !options.cacheDir.empty();
  std::string note;
  ImportResult result = parsedAndBuilt(scene, source, [&] {
    if (cached) return parseCached(source, options, note);
    return source.starts_with(kBuiltinPrefix) ? parseBuiltin(source) : gltf::parseFile(source, options);
  });
  result.cache = std::move(note);
  return result;
}

ImportResult importGltf(Scene& scene, std::span<const std::uint8_t> bytes, const std::string& source,
                        const std::string& baseDir, const ImportOptions& options) {
  return parsedAndBuilt(scene, source, [&] { return gltf::parseBytes(bytes, source, baseDir, options); });
}

}  // namespace tsr::sg
