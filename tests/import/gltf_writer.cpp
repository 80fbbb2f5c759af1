#include "gltf_writer.hpp"

#include <fstream>
#include <random>
#include <span>
#include <stdexcept>

#include "tsr/imageio/image_codec.hpp"

namespace tsr::test {

TempDir::TempDir() {
  std::random_device rd;
  path_ = std::filesystem::temp_directory_path() / ("tsr_import_" + std::to_string(rd()) + std::to_string(rd()));
  std::filesystem::create_directories(path_);
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

std::string base64(const std::vector<std::uint8_t>& b) {
  static const char* t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < b.size(); i += 3) {
    const std::uint32_t n = (std::uint32_t(b[i]) << 16) | (i + 1 < b.size() ? std::uint32_t(b[i + 1]) << 8 : 0) |
                            (i + 2 < b.size() ? b[i + 2] : 0);
    out += t[(n >> 18) & 63];
    out += t[(n >> 12) & 63];
    out += i + 1 < b.size() ? t[(n >> 6) & 63] : '=';
    out += i + 2 < b.size() ? t[n & 63] : '=';
  }
  return out;
}

std::vector<std::uint8_t> readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeBytes(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (!out) throw std::runtime_error("cannot write " + path);
}

void writeText(const std::string& path, const std::string& text) {
  writeBytes(path, std::vector<std::uint8_t>(text.begin(), text.end()));
}

void writePng(const std::string& path, int width, int height, int channels, const std::vector<std::uint8_t>& pixels) {
  imageio::Layout layout;
  layout.width = std::uint32_t(width), layout.height = std::uint32_t(height), layout.channels = std::uint32_t(channels);
  layout.straightAlpha = true;  // as glTF stores it
  imageio::writeFile(path, path, layout, std::as_bytes(std::span(pixels)));
}

GltfBuilder::GltfBuilder() { doc = {{"asset", {{"version", "2.0"}, {"generator", "tsr import tests"}}}}; }

int GltfBuilder::addView(const void* data, std::size_t bytes, std::size_t stride) {
  while (bin.size() % 4) bin.push_back(0);
  nlohmann::json view = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes}};
  if (stride) view["byteStride"] = stride;
  const auto* p = static_cast<const std::uint8_t*>(data);
  bin.insert(bin.end(), p, p + bytes);
  doc["bufferViews"].push_back(view);
  return static_cast<int>(doc["bufferViews"].size()) - 1;
}

int GltfBuilder::addAccessor(int view, int componentType, std::size_t count, const std::string& type, bool normalized,
                             std::size_t byteOffset) {
  nlohmann::json a = {{"bufferView", view}, {"componentType", componentType}, {"count", count}, {"type", type}};
  if (normalized) a["normalized"] = true;
  if (byteOffset) a["byteOffset"] = byteOffset;
  doc["accessors"].push_back(a);
  return static_cast<int>(doc["accessors"].size()) - 1;
}

int GltfBuilder::addFloats(const std::vector<float>& values, const std::string& type) {
  const std::size_t comps = type == "SCALAR" ? 1 : type == "VEC2" ? 2 : type == "VEC3" ? 3 : type == "VEC4" ? 4 : 16;
  return addAccessor(addView(values), kFloat, values.size() / comps, type);
}

void GltfBuilder::writeGltf(const std::string& path, bool dataUri) {
  nlohmann::json d = doc;
  const std::string binName = std::filesystem::path(path).stem().string() + ".bin";
  if (dataUri) {
    d["buffers"] = {{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + base64(bin)}}};
  } else {
    writeBytes((std::filesystem::path(path).parent_path() / binName).string(), bin);
    d["buffers"] = {{{"byteLength", bin.size()}, {"uri", binName}}};
  }
  writeText(path, d.dump(1));
}

void GltfBuilder::writeGlb(const std::string& path) {
  nlohmann::json d = doc;
  d["buffers"] = {{{"byteLength", bin.size()}}};
  std::string json = d.dump();
  while (json.size() % 4) json += ' ';
  std::vector<std::uint8_t> body = bin;
  while (body.size() % 4) body.push_back(0);
  auto u32 = [](std::vector<std::uint8_t>& out, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  };
  std::vector<std::uint8_t> glb = {'g', 'l', 'T', 'F'};
  u32(glb, 2);
  u32(glb, static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + body.size()));
  u32(glb, static_cast<std::uint32_t>(json.size()));
  u32(glb, 0x4E4F534Au);
  glb.insert(glb.end(), json.begin(), json.end());
  u32(glb, static_cast<std::uint32_t>(body.size()));
  u32(glb, 0x004E4942u);
  glb.insert(glb.end(), body.begin(), body.end());
  writeBytes(path, glb);
}

}  // namespace tsr::test
