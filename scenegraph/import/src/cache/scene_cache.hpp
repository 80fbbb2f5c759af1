#pragma once
// The converted-scene cache (ImportOptions::cacheDir): a parsed::Scene kept
// on disk under a key of the source's bytes, the importer's version and the
// import options. An entry is a header (magic, format, importer version,
// key, payload size and hash) and the encoded scene (parsed_scene_codec);
// reading one checks all of it and validates the scene, and any failure is
// a reason to convert again, never an error of the import.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>

#include "parsed_scene.hpp"
#include "tsr/sg/import/importer.hpp"

namespace tsr::sg::cache {

// Bump whenever the conversion of a file, or what a built-in scene's
// generator makes, would give a different parsed::Scene (a test pins the
// built-in scenes to it: BuiltinScenes.ImporterVersionPinsWhatTheyMake).
// 2: materials and the scene carry volumes (KHR_materials_volume, TSR_*).
// 4: cameras carry a thin lens (TSR_camera_lens).
// 6: primitives may be lines or points (glTF modes 0-3).
// 7: built-in scenes are kept too; entries carry the scene unit.
inline constexpr std::uint32_t kImporterVersion = 7;
// An entry's header; the encoded scene follows.
inline constexpr std::size_t kHeaderBytes = 120;

// A file's key: its bytes and the options. A built-in scene's: its
// canonical name alone (the options do not change what it makes), never
// equal to a file's of the same bytes.
std::string key(std::span<const std::uint8_t> source, const ImportOptions& options);
std::string builtinKey(const std::string& canonicalName);
std::filesystem::path entryPath(const std::filesystem::path& dir, const std::string& key);

// The scene, or nothing with `why` set. Its meshes' arrays may be the mapped
// entry's bytes, which stay mapped as long as any scene array holds them.
std::optional<parsed::Scene> load(const std::filesystem::path& entry, const std::string& key, std::string& why);
// Written to a temporary file and renamed into place; false with `why` set on failure.
bool store(const std::filesystem::path& entry, const std::string& key, const parsed::Scene& scene, std::string& why);

}  // namespace tsr::sg::cache
