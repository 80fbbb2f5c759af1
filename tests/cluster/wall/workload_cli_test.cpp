// tessera-render --cluster --aov workload --stats-json end to end: the
// workload image written beside each frame shows, tile by tile, the node
// the client logged in the statistics, the logged tiles cover the frame
// exactly once, and the per-node figures add up the logged tiles.
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <sys/wait.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cluster_test_util.hpp"
#include "tsr/med/image_file.hpp"
#include "wall/workload_check.hpp"

namespace tsr::cluster::test {
namespace {

namespace fs = std::filesystem;

// Exit status of tessera-render with `args`; stderr into `err` when given.
int render(const std::string& args, const fs::path& err = "/dev/null") {
  const std::string command = std::string(TSR_RENDER_BINARY) + " " + args + " --quiet > /dev/null 2>" + err.string();
  return WEXITSTATUS(std::system(command.c_str()));
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string config(const fs::path& dir, const std::string& mode, std::size_t nodes) {
  std::string json = R"({"mode": ")" + mode + R"(", "backend": "embree",
    "parameters": {"spp": 2, "maxDepth": 3, "seed": 5, "threads": 1}, "nodes": [)";
  for (std::size_t i = 0; i < nodes; ++i) json += std::string(i ? "," : "") + R"({"address": "127.0.0.1:1"})";
  json += R"(], "cooperative": {"tileSize": 16, "tolerance": 0})";
  json += "}";
  const fs::path p = dir / (mode + ".json");
  std::ofstream(p) << json;
  return p.string();
}

std::vector<TileWork> loggedTiles(const nlohmann::json& frame) {
  std::vector<TileWork> tiles;
  for (const auto& t : frame.at("tiles")) {
    const auto& r = t.at("rect");
    tiles.push_back(
        {{r[0].get<std::uint32_t>(), r[1].get<std::uint32_t>(), r[2].get<std::uint32_t>(), r[3].get<std::uint32_t>()},
         t.at("node").get<std::size_t>(),
         t.at("milliseconds").get<double>() / 1e3,
         t.at("samples").get<std::uint32_t>(),
         t.at("rays").get<std::uint64_t>(),
         t.at("sync_milliseconds").get<double>() / 1e3});
  }
  return tiles;
}

TEST(WorkloadCli, TheWorkloadImageShowsTheLoggedNodesAndTheTilesCoverEachFrameOnce) {
  TempDir dir;
  TokenFile token("workload token");
  auto nodes = startNodes(3, {"--token-file", token.path()});
  const fs::path stats = dir.path / "stats.json";
  ASSERT_EQ(render("builtin:animated --cluster " + config(dir.path, "cooperative", 3) + " --nodes " + addresses(nodes) +
                   " --token-file " + token.path() + " --size 72x40 --frames 2 --aov workload " + "--stats-json " +
                   stats.string() + " --output " + (dir.path / "f.####.exr").string()),
            0);
  const nlohmann::json j = nlohmann::json::parse(slurp(stats));
  EXPECT_EQ(j.at("mode"), "cooperative");
  EXPECT_EQ(j.at("frames"), 2);
  EXPECT_EQ(j.at("spp"), 2);
  ASSERT_EQ(j.at("per_frame").size(), 2u);
  std::vector<NodeWork> total(3);
  for (std::size_t f = 0; f < 2; ++f) {
    const nlohmann::json& frame = j.at("per_frame")[f];
    const std::string what = "frame " + std::to_string(f);
    const std::vector<TileWork> tiles = loggedTiles(frame);
    expectCoveredExactlyOnce(tiles, 72, 40, what);
    const med::FrameBuffer image =
        med::readImage((dir.path / ("f.000" + std::to_string(f) + ".workload.exr")).string());
    ASSERT_EQ(image.width, 72u);
    expectWorkloadImageMatches(image.colour, 72, 40, tiles, 3, what);
    // Each node's figures are its logged tiles added up; the balance is
    // the slowest node's milliseconds over the mean.
    const FrameWorkload sums = summarizeWorkload(tiles, {}, {0, 1, 2}, 3);
    double slowest = 0, sum = 0;
    for (std::size_t n = 0; n < 3; ++n) {
      const nlohmann::json& node = frame.at("nodes")[n];
      EXPECT_EQ(node.at("tiles"), sums.nodes[n].tiles) << what;
      EXPECT_EQ(node.at("pixels"), sums.nodes[n].pixels) << what;
      EXPECT_EQ(node.at("samples"), sums.nodes[n].pixels * 2) << what;
      EXPECT_EQ(node.at("rays"), sums.nodes[n].rays) << what;
      EXPECT_NEAR(node.at("milliseconds").get<double>(), sums.nodes[n].seconds * 1e3, 1e-6) << what;
      EXPECT_NEAR(node.at("sync_milliseconds").get<double>(), sums.nodes[n].syncSeconds * 1e3, 1e-6) << what;
      slowest = std::max(slowest, node.at("milliseconds").get<double>());
      sum += node.at("milliseconds").get<double>();
      total[n].pixels += sums.nodes[n].pixels;
    }
    EXPECT_NEAR(frame.at("balance").get<double>(), slowest / (sum / 3), 1e-9) << what;
  }
  for (std::size_t n = 0; n < 3; ++n) {
    EXPECT_EQ(j.at("nodes")[n].at("pixels"), total[n].pixels);
    EXPECT_EQ(j.at("nodes")[n].at("address"), nodes[n]->text());
  }
}

TEST(WorkloadCli, TheWorkloadImageAndClusterStatisticsAreRefusedWhereTheyCannotBeMade) {
  TempDir dir;
  const fs::path err = dir.path / "err.txt";
  EXPECT_EQ(render("builtin:cornell --aov workload --output " + (dir.path / "x.png").string(), err), 2);
  EXPECT_NE(slurp(err).find("--aov workload"), std::string::npos) << slurp(err);
  EXPECT_NE(slurp(err).find("--cluster"), std::string::npos) << slurp(err);
  // A stereo pair has two eyes, no one frame to colour: refused before a node is asked.
  EXPECT_EQ(render("builtin:cornell --cluster " + config(dir.path, "stereo", 2) + " --aov workload --output " +
                       (dir.path / "x.png").string(),
                   err),
            2);
  EXPECT_NE(slurp(err).find("stereo"), std::string::npos) << slurp(err);
  EXPECT_EQ(render("builtin:cornell --cluster " + config(dir.path, "cooperative", 1) +
                       " --layers embree,vulkan --stats-json s.json --output " + (dir.path / "x.png").string(),
                   err),
            2);
  EXPECT_NE(slurp(err).find("--stats-json with --cluster and --layers"), std::string::npos) << slurp(err);
  EXPECT_FALSE(fs::exists(dir.path / "x.png"));
}

TEST(WorkloadCli, HelpListsTheWorkloadImageAndTheClusterStatistics) {
  TempDir dir;
  const fs::path out = dir.path / "help.txt";
  ASSERT_EQ(std::system((std::string(TSR_RENDER_BINARY) + " --help > " + out.string()).c_str()), 0);
  const std::string help = slurp(out);
  EXPECT_NE(help.find("workload"), std::string::npos) << help;
  EXPECT_NE(help.find("balance"), std::string::npos) << help;
}

}  // namespace
}  // namespace tsr::cluster::test
