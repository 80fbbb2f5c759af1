#pragma once
// Test helper: assembles glTF documents (JSON via nlohmann, one binary
// buffer) and writes them as .gltf with an external or data-URI buffer, or
// as .glb; plus PNG writing, base64 and a self-removing temp directory.
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace tsr::test {

enum : int { kByte = 5120, kUByte = 5121, kShort = 5122, kUShort = 5123, kUInt = 5125, kFloat = 5126 };

class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::filesystem::path path() const { return path_; }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

std::string base64(const std::vector<std::uint8_t>& bytes);
std::vector<std::uint8_t> readBytes(const std::string& path);
void writeBytes(const std::string& path, const std::vector<std::uint8_t>& bytes);
void writeText(const std::string& path, const std::string& text);
// Writes an 8-bit PNG with OpenImageIO.
void writePng(const std::string& path, int width, int height, int channels, const std::vector<std::uint8_t>& pixels);

class GltfBuilder {
 public:
  GltfBuilder();

  nlohmann::json doc;
  std::vector<std::uint8_t> bin;

  // Appends bytes (4-byte aligned) as a new buffer view; returns its index.
  int addView(const void* data, std::size_t bytes, std::size_t stride = 0);
  template <class T>
  int addView(const std::vector<T>& v, std::size_t stride = 0) {
    return addView(v.data(), v.size() * sizeof(T), stride);
  }
  int addAccessor(int view, int componentType, std::size_t count, const std::string& type, bool normalized = false,
                  std::size_t byteOffset = 0);
  // Tightly packed floats in their own view.
  int addFloats(const std::vector<float>& values, const std::string& type);
  template <class T>
  int addIndices(const std::vector<T>& values) {
    const int ct = sizeof(T) == 1 ? kUByte : sizeof(T) == 2 ? kUShort : kUInt;
    return addAccessor(addView(values), ct, values.size(), "SCALAR");
  }

  // buffers[0] is the binary: an external file next to `path`, or a data URI.
  void writeGltf(const std::string& path, bool dataUri = false);
  void writeGlb(const std::string& path);
};

}  // namespace tsr::test
