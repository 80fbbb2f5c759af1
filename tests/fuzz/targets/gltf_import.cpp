#include <filesystem>

#include "fuzz_targets.hpp"
#include "tsr/sg/import/importer.hpp"
#include "tsr/sg/scene.hpp"

namespace tsr::fuzz {

// Limits far below the defaults keep one input within the fuzzer's memory
// budget; external files resolve against an empty folder, so every uri is
// either refused or not found.
void gltfImport(Bytes bytes) {
  static const std::filesystem::path base = [] {
    auto dir = std::filesystem::temp_directory_path() / "tsr_fuzz_gltf_base";
    std::filesystem::create_directories(dir);
    return dir;
  }();
  sg::ImportOptions options;
  options.maxFileBytes = 1 << 20;
  options.maxJsonValues = 1 << 16;
  options.maxAccessorElements = 1 << 16;
  options.maxImagePixels = 1 << 16;
  sg::Scene scene;
  try {
    sg::importGltf(scene, bytes, "fuzz-input", base.string(), options);
  } catch (const sg::ImportError&) {}
}

}  // namespace tsr::fuzz
