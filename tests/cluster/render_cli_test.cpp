// tessera-render --cluster and --frames end to end: the images written
// through nodes equal the ones written by a local render of the same frames.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <sys/wait.h>

#include <gtest/gtest.h>

#include "cluster_test_util.hpp"
#include "tsr/med/image_file.hpp"
#include "tsr/sg/changes/change_list.hpp"
#include "tsr/sg/wire/wire_codec.hpp"
#include "two_root_scene.hpp"

namespace tsr::cluster::test {
namespace {

namespace fs = std::filesystem;

int run(const std::string& args) {
  std::string command = std::string(TSR_RENDER_BINARY) + " " + args + " --quiet > /dev/null";
  return std::system(command.c_str());
}

std::string writeConfig(const fs::path& dir, const std::string& mode, std::size_t nodes,
                        const std::string& extra = "") {
  std::string json = R"({"mode": ")" + mode + R"(", "backend": "embree",
    "parameters": {"spp": 2, "maxDepth": 3, "seed": 5, "threads": 1}, "nodes": [)";
  for (std::size_t i = 0; i < nodes; ++i) json += std::string(i ? "," : "") + R"({"address": "127.0.0.1:1"})";
  json += "]" + extra + "}";
  fs::path p = dir / (mode + ".json");
  std::ofstream(p) << json;
  return p.string();
}

const std::string kLocal = " --spp 2 --max-depth 3 --seed 5 --threads 1 --size 48x40";

TEST(RenderCli, ClusterImageEqualsLocalImage) {
  TempDir dir;
  TokenFile token("cli token");
  auto nodes = startNodes(2, {"--token-file", token.path()});
  std::string config = writeConfig(dir.path, "cooperative", 2, R"(, "cooperative": {"tileSize": 16})");
  ASSERT_EQ(run("builtin:cornell --cluster " + config + " --nodes " + addresses(nodes) + " --token-file " +
                token.path() + " --size 48x40 --output " + (dir.path / "cluster.exr").string()),
            0);
  ASSERT_EQ(run("builtin:cornell" + kLocal + " --output " + (dir.path / "local.exr").string()), 0);
  EXPECT_TRUE(bitwiseEqual(med::readImage((dir.path / "cluster.exr").string()),
                           med::readImage((dir.path / "local.exr").string())));
}

TEST(RenderCli, PixelFilteredClusterImageAndItsAovsEqualTheLocalOnes) {
  // The filter runs on the client after the tiles are assembled: no seams
  // at tile borders, and the blend factor output comes through too.
  TempDir dir;
  TokenFile token("cli token");
  auto nodes = startNodes(2, {"--token-file", token.path()});
  std::string config = writeConfig(dir.path, "cooperative", 2, R"(, "cooperative": {"tileSize": 16})");
  const std::string filter = " --spp 4 --filter pixel --aov blend --aov indirect";
  ASSERT_EQ(run("builtin:cornell --cluster " + config + " --nodes " + addresses(nodes) + " --token-file " +
                token.path() + " --size 48x40" + filter + " --output " + (dir.path / "cluster.exr").string()),
            0);
  ASSERT_EQ(run("builtin:cornell --max-depth 3 --seed 5 --threads 1 --size 48x40" + filter + " --output " +
                (dir.path / "local.exr").string()),
            0);
  for (const char* image : {"", ".blend", ".indirect"})
    EXPECT_TRUE(bitwiseEqual(med::readImage((dir.path / ("cluster" + std::string(image) + ".exr")).string()),
                             med::readImage((dir.path / ("local" + std::string(image) + ".exr")).string())))
        << "image " << image;
}

TEST(RenderCli, CommandLineParametersBeatTheConfigs) {
  TempDir dir;
  TokenFile token("cli token");
  auto nodes = startNodes(1, {"--token-file", token.path()});
  std::string config = writeConfig(dir.path, "cooperative", 1);  // says spp 2, seed 5
  ASSERT_EQ(run("builtin:cornell --cluster " + config + " --nodes " + addresses(nodes) + " --token-file " +
                token.path() + " --size 32x24 --spp 3 --seed 9 --output " + (dir.path / "cluster.exr").string()),
            0);
  ASSERT_EQ(run("builtin:cornell --spp 3 --max-depth 3 --seed 9 --threads 1 --size 32x24 --output " +
                (dir.path / "local.exr").string()),
            0);
  EXPECT_TRUE(bitwiseEqual(med::readImage((dir.path / "cluster.exr").string()),
                           med::readImage((dir.path / "local.exr").string())));
}

TEST(RenderCli, WrongTokenFailsWithAnError) {
  TempDir dir;
  TokenFile right("right"), wrong("wrong");
  auto nodes = startNodes(1, {"--token-file", right.path()});
  std::string config = writeConfig(dir.path, "cooperative", 1, R"(, "timeouts": {"connectMs": 1000})");
  EXPECT_NE(run("builtin:cornell --cluster " + config + " --nodes " + addresses(nodes) + " --token-file " +
                wrong.path() + " --output " + (dir.path / "x.exr").string() + " 2>/dev/null"),
            0);
  EXPECT_FALSE(fs::exists(dir.path / "x.exr"));
}

TEST(RenderCli, AnOutputTheNodesCannotFillFailsTheFrameWithTheirReason) {
  // Every node would fail the same way: the client says why at once
  // instead of moving the work around until the frame deadline.
  TempDir dir;
  TokenFile token("cli token");
  auto nodes = startNodes(2, {"--token-file", token.path()});
  std::string config = writeConfig(dir.path, "cooperative", 2);
  const fs::path err = dir.path / "err.txt";
  const int status =
      run("builtin:cornell --cluster " + config + " --nodes " + addresses(nodes) + " --token-file " + token.path() +
          " --size 32x24 --aov nosuch --output " + (dir.path / "x.exr").string() + " 2>" + err.string());
  EXPECT_EQ(WEXITSTATUS(status), 2);
  std::ifstream in(err);
  std::string message((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(message.find("nosuch"), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(dir.path / "x.exr"));
}

TEST(RenderCli, AnimatedFramesThroughAWallEqualLocalFrames) {
  TempDir dir;
  auto nodes = startNodes(4);
  std::string config = writeConfig(dir.path, "tiled", 4, R"(, "wall": {"columns": 2, "rows": 2})");
  ASSERT_EQ(run("builtin:animated --cluster " + config + " --nodes " + addresses(nodes) +
                " --size 48x40 --frames 3 --fps 4 --output " + (dir.path / "wall.####.exr").string()),
            0);
  ASSERT_EQ(run("builtin:animated" + kLocal + " --frames 3 --fps 4 --output " + (dir.path / "local.####.exr").string()),
            0);
  for (const char* f : {"0000", "0001", "0002"}) {
    auto wall = med::readImage((dir.path / ("wall." + std::string(f) + ".exr")).string());
    auto local = med::readImage((dir.path / ("local." + std::string(f) + ".exr")).string());
    EXPECT_TRUE(bitwiseEqual(wall, local)) << "frame " << f;
  }
  // The animation moves: frames differ from each other.
  EXPECT_FALSE(bitwiseEqual(med::readImage((dir.path / "local.0000.exr").string()),
                            med::readImage((dir.path / "local.0002.exr").string())));
}

// The size of a part that splits the scene's snapshot in two or more
// (every part still holding its largest container), in KiB.
std::size_t partKiBSplitting(const std::string& source) {
  sg::Scene scene;
  sg::importScene(scene, source);
  scene.commit();
  const sg::ChangeListPtr snapshot = scene.snapshot();
  const std::size_t total = sg::encode(*snapshot).size();
  for (std::size_t parts : {8, 4, 3, 2}) {
    const std::size_t kib = total / parts / 1024;
    if (kib == 0) continue;
    try {
      if (sg::splitSnapshot(snapshot, kib * 1024).size() >= 2) return kib;
    } catch (const std::length_error&) {  // a container larger than the part: larger parts
    }
  }
  ADD_FAILURE() << source << ": no part size splits its " << total << "-byte snapshot";
  return 0;
}

// --temporal photons and object-space pca with --cluster: each node traces
// the photons of every frame ahead of the one shown (Prepare messages feed
// its second replica), and renders its tiles from one viewport per
// sequence; the frames and their direct/indirect parts equal a local
// render's bit for bit, in the cooperative mode whose tiles move between
// nodes as well as on a wall. The cooperative config sends the scene in
// parts ("snapshotPartKiB"), to the nodes' replicas and to the replicas
// ahead that Prepare messages feed.
TEST(RenderCli, TemporalFramesThroughTheClusterEqualLocalFrames) {
  TempDir dir;
  TokenFile token("temporal token");
  auto nodes = startNodes(2, {"--token-file", token.path()});
  const std::size_t partKiB = partKiBSplitting("builtin:animated");
  const std::string cooperative = writeConfig(
      dir.path, "cooperative", 2,
      R"(, "cooperative": {"tileSize": 16, "maxMovesPerFrame": 4}, "snapshotPartKiB": )" + std::to_string(partKiB));
  const std::string wall = writeConfig(dir.path, "tiled", 2, R"(, "wall": {"columns": 2, "rows": 1})");
  const std::string animation = "builtin:animated --frames 4 --fps 4 --aov direct --aov indirect ";
  const std::vector<std::pair<std::string, std::string>> methods = {
      {"photons", "--temporal photons --photons-per-frame 20000 --photon-frames 3"},
      {"objectpca", "--temporal pca --temporal-space object --temporal-window 4 --temporal-overlap 1 "
                    "--photons-per-frame 20000"}};
  for (const auto& [name, method] : methods) {
    ASSERT_EQ(run(animation + kLocal + " " + method + " --output " + (dir.path / (name + ".local.####.exr")).string()),
              0);
    for (const auto& [mode, config] : {std::pair{"cooperative", cooperative}, std::pair{"wall", wall}}) {
      ASSERT_EQ(
          run(animation + method + " --size 48x40 --cluster " + config + " --nodes " + addresses(nodes) +
              " --token-file " + token.path() + " --output " + (dir.path / (name + "." + mode + ".####.exr")).string()),
          0)
          << name << " " << mode;
      for (const char* f : {"0000", "0001", "0002", "0003"})
        for (const char* part : {"", ".direct", ".indirect"}) {
          const std::string stem = name;  // clang 14 cannot capture a structured binding
          auto read = [&](const std::string& who) {
            return med::readImage((dir.path / (stem + "." + who + "." + f + part + ".exr")).string());
          };
          EXPECT_TRUE(bitwiseEqual(read(mode), read("local"))) << name << " " << mode << " frame " << f << part;
        }
    }
  }
}

// --layers with --cluster: the path-traced layer renders cooperatively on
// two nodes, the rasterised marker layer here; the composite equals the
// one of a local layered render bit for bit (the cooperative layer is
// bitwise a local render, and the rest is the same code on the same input).
TEST(RenderCli, ALayeredWindowWithAClusterLayerEqualsTheLocalLayeredRender) {
#ifndef TSR_HAVE_VULKAN_LAYERS
  GTEST_SKIP() << "no Vulkan back-end in this build";
#endif
  TempDir dir;
  TokenFile token("cli token");
  auto nodes = startNodes(2, {"--token-file", token.path()});
  const std::string scene = (dir.path / "two_roots.gltf").string();
  std::ofstream(scene) << tsr::test::twoRootScene();
  std::string config = writeConfig(dir.path, "cooperative", 2, R"(, "cooperative": {"tileSize": 16})");
  const std::string layers = " --layers embree:box,vulkan:markers --aov depth";
  ASSERT_EQ(run(scene + kLocal + layers + " --cluster " + config + " --nodes " + addresses(nodes) + " --token-file " +
                token.path() + " --output " + (dir.path / "cluster.exr").string()),
            0);
  ASSERT_EQ(run(scene + kLocal + layers + " --output " + (dir.path / "local.exr").string()), 0);
  ASSERT_EQ(run(scene + kLocal + " --layers embree:box --output " + (dir.path / "traced.exr").string()), 0);
  const auto cluster = med::readImage((dir.path / "cluster.exr").string());
  const auto local = med::readImage((dir.path / "local.exr").string());
  EXPECT_TRUE(bitwiseEqual(cluster, local));
  EXPECT_TRUE(bitwiseEqual(med::readImage((dir.path / "cluster.depth.exr").string()),
                           med::readImage((dir.path / "local.depth.exr").string())));
  // Not just the path-traced layer: the marker is composited in.
  const auto traced = med::readImage((dir.path / "traced.exr").string());
  std::size_t marker = 0;
  for (std::size_t i = 0; i < cluster.colour.size(); ++i)
    marker += cluster.colour[i] != traced.colour[i] && cluster.colour[i].g > 0.9f && cluster.colour[i].r < 0.2f;
  EXPECT_GT(marker, 10u) << "the right half of the marker shows, not just stray edge pixels";
  // A sequence of such windows: the scene does not move, every frame is the same image.
  ASSERT_EQ(run(scene + kLocal + layers + " --cluster " + config + " --nodes " + addresses(nodes) + " --token-file " +
                token.path() + " --frames 2 --output " + (dir.path / "frame.####.exr").string()),
            0);
  for (const char* f : {"0000", "0001"})
    EXPECT_TRUE(bitwiseEqual(med::readImage((dir.path / ("frame." + std::string(f) + ".exr")).string()), local)) << f;
}

TEST(RenderCli, AClusterLayerNeedsExactlyOneLayerOfTheNodesBackEndAndNoOtherBackEnd) {
  TempDir dir;
  std::string config = writeConfig(dir.path, "cooperative", 1, R"(, "timeouts": {"connectMs": 200})");
  const fs::path err = dir.path / "err.txt";
  auto refused = [&](const std::string& layers, const std::string& why) {
    const int status = run("builtin:cornell --size 8x8 --layers " + layers + " --cluster " + config + " --output " +
                           (dir.path / "x.exr").string() + " 2>" + err.string());
    EXPECT_EQ(WEXITSTATUS(status), 2) << layers;
    std::ifstream in(err);
    std::string message((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_NE(message.find(why), std::string::npos) << message;
  };
  refused("vulkan", "no layer");
  refused("embree,embree", "several layers");
  const int status = run("builtin:cornell --size 8x8 --backend vulkan --cluster " + config + " --output " +
                         (dir.path / "x.exr").string() + " 2>" + err.string());
  EXPECT_EQ(WEXITSTATUS(status), 2) << "the config names the nodes' back-end, not --backend";
}

TEST(RenderCli, OnMixedBackEndsEachOptionReachesTheNodesThatTakeIt) {
  // configs/mixed-backends.json: a path-traced and a rasterised eye. --spp
  // is the path tracer's, msaa the rasterizer's; neither fails the other
  // node, and a name neither back-end takes is still refused.
  TempDir dir;
  TokenFile token("cli token");
  auto nodes = startNodes(2, {"--token-file", token.path()});
  const fs::path config = dir.path / "mixed.json";
  std::ofstream(config) << R"({"mode": "stereo", "backend": "embree", "parameters": {"spp": 2, "seed": 1},
    "nodes": [{"address": "127.0.0.1:1"}, {"address": "127.0.0.1:2", "backend": "vulkan", "parameters": {}}],
    "stereo": {"compose": "side-by-side"}})";
  const std::string common = "builtin:cornell --size 32x24 --cluster " + config.string() + " --nodes " +
                             addresses(nodes) + " --token-file " + token.path() + " --output ";
  EXPECT_EQ(run(common + (dir.path / "a.exr").string() + " --spp 3 --param msaa=4"), 0);
  EXPECT_TRUE(fs::exists(dir.path / "a.exr"));
  EXPECT_EQ(WEXITSTATUS(run(common + (dir.path / "b.exr").string() + " --param nosuch=1 2>/dev/null")), 2);
  EXPECT_FALSE(fs::exists(dir.path / "b.exr"));
}

TEST(RenderCli, FramesNeedAFrameNumberInTheOutputName) {
  EXPECT_NE(run("builtin:animated --frames 2 --output /tmp/no-hashes.exr 2>/dev/null"), 0);
  EXPECT_NE(run("builtin:cornell --nodes 127.0.0.1:1 2>/dev/null"), 0);
}

}  // namespace
}  // namespace tsr::cluster::test
