// Writes the seed corpora of the fuzz targets from real data: encoded change
// lists of the built-in scenes (snapshot, then animated frames), the
// messages of one cluster frame as the client and a node send them, pixel
// tiles as nodes encode them, the glTF files the import tests write, and
// the shipped cluster configurations.
//   make_fuzz_corpus CORPUS_DIR CONFIG_DIR
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "cache/scene_cache.hpp"
#include "gltf_writer.hpp"
#include "test_scenes.hpp"
#include "tsr/cluster/messages.hpp"
#include "tsr/cluster/pixel_codec.hpp"
#include "tsr/sg/import/importer.hpp"
#include "tsr/sg/scene.hpp"
#include "tsr/sg/wire/wire_codec.hpp"

namespace {

namespace fs = std::filesystem;
using Bytes = std::vector<std::uint8_t>;

void put(const fs::path& dir, const std::string& name, const Bytes& bytes) {
  fs::create_directories(dir);
  std::ofstream(dir / name, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

Bytes concat(const std::vector<Bytes>& parts) {
  Bytes out;
  for (const Bytes& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

tsr::med::FrameBuffer gradient(std::uint32_t w, std::uint32_t h, const std::vector<std::string>& outputs) {
  tsr::med::FrameBuffer fb(w, h);
  for (std::uint32_t y = 0; y < h; ++y)
    for (std::uint32_t x = 0; x < w; ++x) {
      fb.colour[fb.index(x, y)] = {x / float(w), y / float(h), 0.5f, 1.0f};
      fb.depth[fb.index(x, y)] = (x + y) % 5 == 0 ? tsr::med::kNoDepth : 1.0f + 0.01f * float(x);
    }
  for (const std::string& name : outputs) fb.outputs[name] = fb.colour;
  return fb;
}

// The rich test scene (every container type, textures as images) as a
// snapshot, then a frame that moves, edits and deletes. Built-in scenes hold
// 50-140 KB of sphere meshes, too big for seeds: only their deltas are kept.
std::vector<Bytes> richStream() {
  tsr::test::TempDir tmp;
  tsr::test::richScene(tmp).writeGltf(tmp.file("rich.gltf"), true);
  tsr::sg::Scene scene;
  tsr::sg::importScene(scene, tmp.file("rich.gltf"));
  scene.commit();
  std::vector<Bytes> lists{tsr::sg::encode(*scene.snapshot())};
  tsr::sg::Scene animated;
  const auto imported = tsr::sg::importScene(animated, "builtin:animated");
  animated.commit();
  for (int f = 1; f <= 2; ++f) {
    for (const auto& a : imported.animations) a.apply(animated, 0.1f * static_cast<float>(f));
    lists.push_back(tsr::sg::encode(*animated.commit()));
  }
  return lists;
}

void wireCodec(const fs::path& dir) {
  const std::vector<Bytes> lists = richStream();
  put(dir, "rich-snapshot", lists[0]);
  put(dir, "animated-deltas", concat({lists[1], lists[2]}));
  put(dir, "stream", concat(lists));
}

void clusterMessages(const fs::path& dir) {
  using namespace tsr::cluster;
  const auto frame = [](const Frame& f) { return *f; };
  Hello hello;
  hello.clientName = "client";
  hello.clientNonce.fill(7);
  Challenge challenge;
  challenge.nodeNonce.fill(3);
  Welcome welcome{"node-a", 2, {"embree", "vulkan", "coverage"}};
  put(dir, "handshake",
      concat({frame(makeFrame(hello)), frame(makeFrame(challenge)), frame(makeFrame(Auth{})), frame(makeFrame(welcome)),
              frame(makeFrame(Reject{"wrong token"}))}));

  const std::vector<Bytes> lists = richStream();
  std::vector<Bytes> replica{frame(frameFromPayload(Snapshot::kType, lists[0]))};
  for (std::size_t i = 1; i < lists.size(); ++i) replica.push_back(frame(frameFromPayload(Changes::kType, lists[i])));
  replica.push_back(frame(makeFrame(Applied{2})));
  put(dir, "replica", concat(replica));

  ViewportSpec spec{1, "embree", 1, 2, {}};
  spec.parameters.set("spp", std::int64_t{4});
  spec.parameters.set("threshold", 0.01);
  tsr::med::View view;
  view.width = 64;
  view.height = 48;
  view.region = {0, 0, 64, 48};
  RenderJob job{1, view, {{0, 0, 32, 24}, {32, 24, 64, 48}}, {"albedo"}, true};
  RenderRequest request{9, Compression::Lz4, {job}};
  RenderTile tile;
  tile.frame = 9;
  tile.viewport = 1;
  tile.rect = {0, 0, 8, 8};
  tile.seconds = 0.01;
  tile.samples = 4;
  tile.rays = 1536;
  tile.outputs = {"albedo"};
  EncodedPixels px = encodePixels(gradient(8, 8, tile.outputs), Compression::Lz4, tile.outputs);
  tile.compression = px.compression;
  tile.pixels = px.bytes;
  put(dir, "frame",
      concat({frame(makeFrame(SetViewports{{spec}})), frame(makeFrame(request)), frame(makeFrame(tile)),
              frame(makeFrame(FrameDone{9, 0.02})), frame(makeFrame(Swap{9}))}));
  // An animation for viewports that look ahead: frames ahead, then one shown.
  RenderRequest shown{10, Compression::Lz4, {job}, 0};
  put(dir, "sequence",
      concat(
          {frame(makeFrame(Prepare{0, lists[0]})), frame(makeFrame(Prepare{1, lists[1]})), frame(makeFrame(shown))}));
  put(dir, "service",
      concat({frame(makeFrame(HashQuery{5})), frame(makeFrame(HashReply{5, 2, 0xabcdef})),
              frame(makeFrame(Heartbeat{1})), frame(makeFrame(HeartbeatAck{1})),
              frame(makeFrame(ErrorReport{ErrorReport::Kind::RenderFailed, "no such viewport"})),
              frame(makeFrame(Bye{}))}));
}

void pixelCodec(const fs::path& dir) {
  using tsr::cluster::Compression;
  const std::vector<std::string> names{"albedo", "normal", "variance"};
  for (Compression c : {Compression::None, Compression::Lz4, Compression::Zstd})
    for (std::uint8_t n : {0, 2}) {
      const std::vector<std::string> outputs(names.begin(), names.begin() + n);
      const auto px = tsr::cluster::encodePixels(gradient(6, 5, outputs), c, outputs);
      Bytes input{5, 4, static_cast<std::uint8_t>(px.compression), n};  // width 6, height 5: 1 + byte % 64
      input.insert(input.end(), px.bytes.begin(), px.bytes.end());
      put(dir, "tile-c" + std::to_string(int(c)) + "-o" + std::to_string(n), input);
    }
}

void gltfImport(const fs::path& dir) {
  tsr::test::TempDir tmp;
  tsr::test::tinyScene().writeGltf(tmp.file("tiny.gltf"), true);
  tsr::test::tinyScene().writeGlb(tmp.file("tiny.glb"));
  tsr::test::richScene(tmp).writeGltf(tmp.file("rich.gltf"), true);
  tsr::test::richScene(tmp).writeGlb(tmp.file("rich.glb"));
  for (const char* name : {"tiny.gltf", "tiny.glb", "rich.gltf", "rich.glb"})
    put(dir, name, tsr::test::readBytes(tmp.file(name)));
}

// The scene part of a real import-cache entry (what follows the checked
// header), so a change of the cache's format re-makes this seed. (The rich
// scene names image files, and such files are not cached.)
void importCache(const fs::path& dir) {
  tsr::test::TempDir tmp;
  tsr::test::tinyScene().writeGltf(tmp.file("tiny.gltf"), true);
  tsr::sg::ImportOptions options;
  options.cacheDir = tmp.file("cache");
  tsr::sg::Scene scene;
  tsr::sg::importScene(scene, tmp.file("tiny.gltf"), options);
  for (const auto& e : fs::directory_iterator(options.cacheDir)) {
    const Bytes entry = tsr::test::readBytes(e.path().string());
    if (entry.size() > tsr::sg::cache::kHeaderBytes)
      put(dir, "tiny", Bytes(entry.begin() + tsr::sg::cache::kHeaderBytes, entry.end()));
  }
}

void clusterConfig(const fs::path& dir, const fs::path& configs) {
  for (const auto& e : fs::directory_iterator(configs))
    if (e.path().extension() == ".json")
      put(dir, e.path().filename().string(), tsr::test::readBytes(e.path().string()));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: make_fuzz_corpus CORPUS_DIR CONFIG_DIR\n";
    return 2;
  }
  const fs::path out = argv[1];
  wireCodec(out / "wire_codec");
  clusterMessages(out / "cluster_messages");
  pixelCodec(out / "pixel_codec");
  gltfImport(out / "gltf_import");
  importCache(out / "import_cache");
  clusterConfig(out / "cluster_config", argv[2]);
  return 0;
}
