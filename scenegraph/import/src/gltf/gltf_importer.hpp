#pragma once
// Turns a glTF file into a checked parsed scene, or throws ImportError.
#include <span>
#include <string>

#include "parsed_scene.hpp"
#include "tsr/sg/import/importer.hpp"

namespace tsr::sg::gltf {

parsed::Scene parseFile(const std::string& path, const ImportOptions& options);
parsed::Scene parseBytes(std::span<const unsigned char> bytes, const std::string& source, const std::string& baseDir,
                         const ImportOptions& options);

}  // namespace tsr::sg::gltf
