#pragma once
// Loads a scene description into a Scene: a glTF 2.0 file (.gltf or .glb)
// or a built-in scene ("builtin:cornell", "builtin:instances:N",
// "builtin:animated", "builtin:plant:TRIANGLES"). Everything is parsed and validated before the first
// container is created, so a failed import leaves the scene untouched.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "tsr/sg/import/animation.hpp"
#include "tsr/sg/import/import_error.hpp"
#include "tsr/sg/types.hpp"

namespace tsr::sg {

class Scene;

struct ImportOptions {
  // glTF requires primitives without normals to be shaded flat, so by
  // default they keep none and every back-end shades them with the
  // triangle's own normal. smoothNormals instead generates per-vertex normals
  // (the triangles sharing a vertex averaged, weighted by area).
  bool smoothNormals = false;
  // Files (.gltf, .glb, external buffers and images) larger than this are
  // refused before they are read: 256 MiB holds any scene a glTF's JSON
  // describes by hand and most binary ones; raise it for bigger scans.
  std::uint64_t maxFileBytes = std::uint64_t{256} << 20;
  // A glTF whose JSON holds more values than this (every number, string,
  // array element and object member counts) is refused by a cheap scan
  // before it is parsed: a parsed value costs 16 to 100 bytes, twice over
  // (our checks and tinygltf), so 4 Mi values stay within about 1 GB while
  // a scene with 200,000 nodes needs well under that count.
  std::uint64_t maxJsonValues = std::uint64_t{1} << 22;
  // Accessors with more elements than this are refused.
  std::uint64_t maxAccessorElements = std::uint64_t{1} << 28;
  // Decoded images with more pixels than this are refused.
  std::uint64_t maxImagePixels = std::uint64_t{1} << 28;
  // Non-empty: a folder for converted scenes (the seed's pre-converted
  // database). A file's conversion is kept there under a key of its bytes'
  // hash, the importer's version and these options, and read back instead
  // of parsing the file again; an entry that does not check out (wrong key
  // or version, damaged, truncated, invalid) is refused and rebuilt. Files
  // that name external buffers or images are not kept. A built-in scene is
  // kept under its name (and the importer's version).
  std::string cacheDir = {};
};

// What an import produced, in numbers.
struct ImportCounts {
  std::size_t nodes = 0;       // Transforms created for source nodes
  std::size_t geometries = 0;  // Geometry containers (unique meshes' primitives)
  std::size_t materials = 0;
  std::size_t images = 0;
  std::size_t uniqueTriangles = 0;  // over Geometry containers, not instances
  std::size_t skippedPrimitives = 0;
};

struct ImportResult {
  ContainerId root = kNoContainer;  // a Group holding the top-level nodes
  std::vector<ContainerId> cameras;
  std::vector<ContainerId> lights;  // unique Light containers
  ContainerId background = kNoContainer;
  std::vector<Animation> animations;
  std::vector<std::string> warnings;
  ImportCounts counts;
  // The length of one scene unit in metres (glTF: 1; builtin:cornell and the
  // scenes built on it: 0.001). Physical settings — an f-number, the eyes'
  // separation — convert through it.
  float metresPerUnit = 1.0f;
  // With ImportOptions::cacheDir: "hit", "stored", "rebuilt (REASON)" or
  // "not stored (REASON)"; empty without a cache.
  std::string cache = {};
};

// Throws ImportError ("<source>: <reason>") for anything it cannot load.
ImportResult importScene(Scene& scene, const std::string& source, const ImportOptions& options = {});
// A .gltf or .glb (told apart by its first bytes) held in memory, named
// `source` in errors; its external buffers and images resolve inside
// baseDir, which they may not leave.
ImportResult importGltf(Scene& scene, std::span<const std::uint8_t> bytes, const std::string& source,
                        const std::string& baseDir, const ImportOptions& options = {});

// The names importScene accepts after "builtin:", as written in messages.
std::vector<std::string> builtinSceneNames();

}  // namespace tsr::sg
