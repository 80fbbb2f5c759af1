#pragma once
// Reads glTF accessors into plain arrays, checking every byte range against
// its buffer view and buffer, element counts against the import limits and
// floats for NaN and infinity.
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "tsr/sg/import/importer.hpp"

namespace tsr::sg::gltf {

// An integer component of a normalized accessor as glTF maps it to [0, 1]
// or [-1, 1]; other component types are returned as they are.
float normalizedInteger(float value, int componentType);

class AccessorReader {
 public:
  AccessorReader(const tinygltf::Model& model, std::string source, const ImportOptions& options)
      : model_(model),
        source_(std::move(source)),
        options_(options),
        quantized_(std::find(model.extensionsUsed.begin(), model.extensionsUsed.end(), "KHR_mesh_quantization") !=
                   model.extensionsUsed.end()) {}

  // Components as floats, `components` per element (1 to 4, or 16 for
  // MAT4). Integer components are accepted only when `normalizedInts` is
  // set and the accessor is normalized, or in a file that uses
  // KHR_mesh_quantization (8 and 16-bit, normalized or not); they are
  // mapped as glTF says.
  std::vector<float> floats(int accessor, int components, bool normalizedInts, const std::string& what) const;
  // Unsigned 8, 16 or 32-bit scalars.
  std::vector<std::uint32_t> indices(int accessor, const std::string& what) const;
  std::size_t count(int accessor, const std::string& what) const;
  // The bytes of a buffer view, checked against its buffer.
  std::vector<std::uint8_t> viewBytes(int view, const std::string& what) const;

 private:
  const tinygltf::Accessor& accessor(int index, const std::string& what) const;
  [[noreturn]] void fail(const std::string& reason) const;

  const tinygltf::Model& model_;
  std::string source_;
  const ImportOptions& options_;
  bool quantized_;
};

}  // namespace tsr::sg::gltf
