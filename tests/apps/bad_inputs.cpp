#include "bad_inputs.hpp"

#include <cstdint>
#include <cstring>
#include <fstream>

namespace tsr::test {
namespace {

namespace fs = std::filesystem;

// Three float32 vertices; the second and third hold inf and NaN.
constexpr const char* kTriangle = "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA";
constexpr const char* kInfVertex = "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgH8AAAAA";
constexpr const char* kNanVertex = "AAAAAAAAAAAAAAAAAADAfwAAAAAAAAAAAAAAAAAAgD8AAAAA";

void write(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

// One node with one triangle whose 36-byte buffer is `uri`.
std::string triangleGltf(const std::string& uri, const std::string& node = "\"mesh\": 0",
                         const std::string& byteLength = "36", const std::string& count = "3") {
  return R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "nodes": [{)" + node +
         R"(}], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": )" +
         count + R"(, "type": "VEC3"}],
  "bufferViews": [{"buffer": 0, "byteLength": 36}],
  "buffers": [{"byteLength": )" +
         byteLength + R"(, "uri": ")" + uri + R"("}]})";
}

// A triangle whose node is animated to an infinite translation at t = 1.
constexpr const char* kInfiniteAnimation =
    R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
                {"bufferView": 1, "componentType": 5126, "count": 2, "type": "SCALAR", "min": [0], "max": [1]},
                {"bufferView": 2, "componentType": 5126, "count": 2, "type": "VEC3"}],
  "bufferViews": [{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 8},
                  {"buffer": 0, "byteOffset": 44, "byteLength": 24}],
  "buffers": [{"byteLength": 68, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAgD8AAAAAAAAAAAAAAAAAAAAAAACAfwAAAAA="}],
  "animations": [{"samplers": [{"input": 1, "output": 2}], "channels": [{"sampler": 0, "target": {"node": 0, "path": "translation"}}]}]})";

std::string dataUri(const char* base64) { return std::string("data:application/octet-stream;base64,") + base64; }

std::string imageGltf(const std::string& uri) {
  return R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": []}], "images": [{"uri": ")" + uri + R"("}]})";
}

std::string glbOf(const std::string& json) {
  std::string padded = json;
  while (padded.size() % 4) padded += ' ';
  const std::uint32_t total = 20 + static_cast<std::uint32_t>(padded.size()), version = 2,
                      jsonLength = static_cast<std::uint32_t>(padded.size()), jsonType = 0x4E4F534A;
  std::string out = "glTF";
  for (std::uint32_t v : {version, total, jsonLength, jsonType}) out.append(reinterpret_cast<const char*>(&v), 4);
  return out + padded;
}

}  // namespace

std::vector<BadInput> writeBadSceneInputs(const fs::path& dir) {
  fs::create_directories(dir / "scene" / "folder.gltf");
  const std::string secret = (dir / "secret.bin").string();
  {
    const std::uint8_t bytes[36] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0x80, 0x3f, 0, 0,
                                    0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0x80, 0x3f, 0, 0};
    std::ofstream(secret, std::ios::binary).write(reinterpret_cast<const char*>(bytes), sizeof bytes);
  }
  write(dir / "scene" / "empty.gltf", "");
  const std::string glb = glbOf(triangleGltf(dataUri(kTriangle)));
  write(dir / "scene" / "truncated.glb", glb.substr(0, glb.size() / 2));
  write(dir / "scene" / "up.gltf", triangleGltf("../secret.bin"));
  write(dir / "scene" / "passwd.gltf", triangleGltf("../../etc/passwd"));
  write(dir / "scene" / "encoded-up.gltf", triangleGltf("..%2Fsecret.bin"));
  write(dir / "scene" / "absolute.gltf", triangleGltf(secret));
  write(dir / "scene" / "file-scheme.gltf", triangleGltf("file://" + secret));
  write(dir / "scene" / "http-scheme.gltf", triangleGltf("http://127.0.0.1:9/secret.bin"));
  write(dir / "scene" / "huge-buffer.gltf", triangleGltf(dataUri(kTriangle), "\"mesh\": 0", "1000000000000000"));
  write(dir / "scene" / "huge-count.gltf", triangleGltf(dataUri(kTriangle), "\"mesh\": 0", "36", "4000000000"));
  write(dir / "scene" / "inf-translation.gltf",
        triangleGltf(dataUri(kTriangle), "\"mesh\": 0, \"translation\": [0, 1e400, 0]"));
  write(dir / "scene" / "inf-vertex.gltf", triangleGltf(dataUri(kInfVertex)));
  write(dir / "scene" / "nan-vertex.gltf", triangleGltf(dataUri(kNanVertex)));
  write(dir / "scene" / "inf-animation.gltf", kInfiniteAnimation);
  write(dir / "scene" / "bad-image-uri.gltf", imageGltf("data:image/png;base64,iVBORw0KGgoAAAA="));
  write(dir / "scene" / "bad-jpeg.gltf",
        imageGltf("data:image/jpeg;base64,/9j/4AAQSkZJRgABAQAAAQABAAD/2wBDAAgGBgcGBQ=="));
  write(dir / "scene" / "not-a.png", "this is no PNG");
  write(dir / "scene" / "bad-image-file.gltf", imageGltf("not-a.png"));
  return {
      {"missing file", "scene/missing.gltf", "no such file"},
      {"directory", "scene/folder.gltf", "it is a directory"},
      {"empty file", "scene/empty.gltf", "invalid JSON"},
      {"truncated glb", "scene/truncated.glb", "GLB header says"},
      {"buffer in the parent folder", "scene/up.gltf", "leaves the glTF file's folder"},
      {"../../etc/passwd", "scene/passwd.gltf", "leaves the glTF file's folder"},
      {"percent-encoded ..", "scene/encoded-up.gltf", "leaves the glTF file's folder"},
      {"absolute path", "scene/absolute.gltf", "is an absolute path"},
      {"file: uri", "scene/file-scheme.gltf", "has a scheme"},
      {"http: uri", "scene/http-scheme.gltf", "has a scheme"},
      {"huge buffer byteLength", "scene/huge-buffer.gltf", "buffer 0 declares 1000000000000000 bytes"},
      {"huge accessor count", "scene/huge-count.gltf", "accessor 0"},
      {"infinite translation", "scene/inf-translation.gltf", "1e400"},
      {"infinite vertex", "scene/inf-vertex.gltf", "finite"},
      {"NaN vertex", "scene/nan-vertex.gltf", "finite"},
      {"infinite animated translation", "scene/inf-animation.gltf",
       "animation 0 channel 0 output) element 1 is not finite"},
      {"truncated PNG", "scene/bad-image-uri.gltf", "image 0 is a truncated PNG"},
      {"JPEG that does not decode", "scene/bad-jpeg.gltf", "image 0"},
      {"image file that is no image", "scene/bad-image-file.gltf", "image 0 ('not-a.png') is neither PNG nor JPEG"},
  };
}

std::vector<BadInput> writeBadScriptFiles(const fs::path& dir) {
  fs::create_directories(dir / "scripts" / "folder.txt");
  write(dir / "scripts" / "binary.txt", std::string("\x7f"
                                                    "ELF\0\0\0\x01\n",
                                                    9));
  std::string large;
  while (large.size() <= (std::size_t{2} << 20)) large += "# a comment line of padding\n";
  write(dir / "scripts" / "large.txt", large);
  write(dir / "scripts" / "unknown.txt", "# fine so far\nfly 3\n");
  return {
      {"missing script", "scripts/missing.txt", "scripts/missing.txt: no such file"},
      {"script folder", "scripts/folder.txt", "scripts/folder.txt: it is a directory"},
      {"binary script", "scripts/binary.txt", "a NUL byte"},
      {"2 MiB script", "scripts/large.txt", "scripts/large.txt: larger than"},
      {"unknown action", "scripts/unknown.txt", "unknown action 'fly'"},
  };
}

}  // namespace tsr::test
