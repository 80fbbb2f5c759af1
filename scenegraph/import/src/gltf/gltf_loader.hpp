#pragma once
// Reads a .gltf or .glb file and runs tinygltf on it, after the JSON has
// passed the type checks of gltf_validation. Images are not decoded here:
// the bytes of images given by uri are kept in tinygltf::Image::image,
// those in buffer views are left for the importer to slice with checks.
#include <span>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "files/mapped_file.hpp"
#include "gltf/draco_primitive.hpp"
#include "tsr/sg/import/importer.hpp"

namespace tsr::sg::gltf {

struct LoadedFile {
  tinygltf::Model model;
  DracoIndices dracoIndices;  // KHR_draco_mesh_compression (draco_primitive.hpp)
  std::vector<std::string> warnings;
  bool readOtherFiles = false;  // external buffers or images were read
};

// The whole source file mapped, within options.maxFileBytes.
MappedFile mapSource(const std::string& path, const ImportOptions& options);

LoadedFile loadFile(const std::string& path, const ImportOptions& options);
// The same for a file's bytes; external buffers and images resolve inside
// baseDir only (empty: the working directory), named `source` in errors.
LoadedFile loadBytes(std::span<const unsigned char> bytes, const std::string& source, const std::string& baseDir,
                     const ImportOptions& options);

}  // namespace tsr::sg::gltf
