#pragma once
// --max-file-mb and --max-elements: the bounds every program that reads
// scene files puts on them, and --import-cache, where it keeps converted
// scenes; declared the same way everywhere.
#include <CLI/CLI.hpp>

#include <cstdint>
#include <string>

#include "tsr/sg/import/importer.hpp"

namespace tsr::app {

// The help of a SCENE argument, naming every built-in scene the importer has.
inline std::string sceneArgumentHelp() {
  std::string help = "a .gltf/.glb file or one of the built-in scenes";
  const char* separator = " ";
  for (const std::string& name : sg::builtinSceneNames()) help += separator + ("builtin:" + name), separator = ", ";
  return help;
}

class ImportLimitOptions {
 public:
  // Declares both options on `app`; --max-elements writes to `import` at
  // once, --max-file-mb when apply() is called after parsing.
  void add(CLI::App& app, sg::ImportOptions& import) {
    maxFileMb_ = import.maxFileBytes >> 20;
    app.add_option("--max-file-mb", maxFileMb_, "largest scene file (.gltf, .glb, buffer, image) read, in MiB")
        ->check(CLI::Range(std::uint64_t{1}, std::uint64_t{1} << 20));
    app.add_option("--max-elements", import.maxJsonValues,
                   "most values a glTF's JSON may hold; larger files are refused before parsing")
        ->check(CLI::Range(std::uint64_t{1}, std::uint64_t{1} << 40));
    app.add_option(
        "--import-cache", import.cacheDir,
        "folder for converted scenes: a file's (or built-in scene's) second load reads its conversion from there");
  }
  void apply(sg::ImportOptions& import) const { import.maxFileBytes = maxFileMb_ << 20; }

 private:
  std::uint64_t maxFileMb_ = 0;
};

}  // namespace tsr::app
