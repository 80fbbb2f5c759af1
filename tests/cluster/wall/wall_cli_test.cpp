// tessera-wall end to end on real node processes presenting to files: the
// presented tiles stitch to one local render of the same frame; a node that
// dies leaves the others presenting with its screen marked, and is taken
// back when it returns; a wall that is not a grid stitches too.
#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <regex>
#include <thread>

#include <gtest/gtest.h>

#include "tsr/cluster/wall_layout.hpp"
#include "tsr/med/image_file.hpp"
#include "wall/wall_test_util.hpp"
#include "wall/workload_check.hpp"

namespace tsr::cluster::test {
namespace {

using namespace std::chrono_literals;

TEST(WallCli, FourNodesPresentTilesThatStitchToTheLocalRender) {
  TempDir dir;
  Wall wall(dir.path, 4);
  fs::path log = dir.path / "wall.log";
  ASSERT_EQ(runWall(gridConfig(dir.path) + " builtin:animated --nodes " + wall.addresses() +
                        " --frames 3 --size 48x40 --output " + (dir.path / "wall.exr").string(),
                    log),
            0)
      << slurp(log);
  // Frames 1..3 of the wall pose the animation at 0, 1/24, 2/24 s.
  med::FrameBuffer ref = localFrame(2, 48, 40);
  auto rects = wallLayout(48, 40, 2, 2, 0);
  for (std::size_t i = 0; i < 4; ++i) {
    for (int wait = 0; wait < 200 && wall.newestFrame(i) < 3; ++wait) std::this_thread::sleep_for(20ms);
    ASSERT_EQ(wall.newestFrame(i), 3u) << "node " << i;
    expectTileEquals(wall.tile(i, 3, rects[i]), ref, rects[i], "node " + std::to_string(i));
  }
  // The client's stitched frame too (a grid without bezels covers every pixel).
  med::FrameBuffer stitched = med::readImage((dir.path / "wall.exr").string());
  expectTileEquals(stitched, ref, {0, 0, 48, 40}, "the stitched frame");
  std::string out = slurp(log);
  EXPECT_NE(out.find("4 of 4 nodes online"), std::string::npos) << out;
  EXPECT_NE(out.find("fps"), std::string::npos) << out;
}

// The lens and the shutter reach the nodes with the view (the animation's
// motion with the scene): each stitched frame equals a local render with
// the same camera; bad values are one error line naming the option.
TEST(WallCli, TheLensAndTheShutterReachTheNodes) {
  TempDir dir;
  Wall wall(dir.path, 4);
  fs::path log = dir.path / "wall.log";
  const std::string args = gridConfig(dir.path) + " builtin:animated --nodes " + wall.addresses();
  struct Case {
    std::string options, bad;
    float aperture, focus;
    sg::Vec2 shutter;
  };
  for (const Case& c : {Case{"--aperture 0.3 --focus-distance 2", "--aperture -1", 0.3f, 2.0f, {0, 0}},
                        Case{"--shutter 0,1", "--shutter 0.5,0.2", 0.0f, 5.0f, {0, 1}}}) {
    ASSERT_EQ(
        runWall(args + " --frames 1 --size 48x40 " + c.options + " --output " + (dir.path / "wall.exr").string(), log),
        0)
        << slurp(log);
    const med::FrameBuffer stitched = med::readImage((dir.path / "wall.exr").string());
    expectTileEquals(stitched, localFrame(0, 48, 40, c.aperture, c.focus, c.shutter), {0, 0, 48, 40}, c.options);
    EXPECT_NE(stitched.colour, localFrame(0, 48, 40).colour) << c.options << " shows";
    ASSERT_NE(runWall(args + " " + c.bad, log), 0);
    EXPECT_NE(slurp(log).find(c.bad.substr(0, c.bad.find(' '))), std::string::npos) << slurp(log);
  }
}

// --seed-per-frame: frame f of the wall draws seed + f on every node, the
// same picture a local render with that seed makes.
TEST(WallCli, SeedPerFrameReachesTheNodes) {
  TempDir dir;
  Wall wall(dir.path, 4);
  fs::path log = dir.path / "wall.log";
  ASSERT_EQ(runWall(gridConfig(dir.path) + " builtin:animated --nodes " + wall.addresses() +
                        " --frames 2 --size 48x40 --seed-per-frame --output " + (dir.path / "wall.exr").string(),
                    log),
            0)
      << slurp(log);
  const med::FrameBuffer stitched = med::readImage((dir.path / "wall.exr").string());
  expectTileEquals(stitched, localFrame(1, 48, 40, 0.0f, 5.0f, {0, 0}, 6), {0, 0, 48, 40}, "frame 1, seed 5 + 1");
  EXPECT_NE(stitched.colour, localFrame(1, 48, 40).colour) << "not the config's seed";
}

// --workload beside: the status lines name each screen's share and the
// balance, and FILE.workload.EXT beside --output shows each screen in its
// node's colour; over: the frame itself carries the colours, half and half.
TEST(WallCli, TheWorkloadImageGoesBesideTheFrameOrOverIt) {
  TempDir dir;
  Wall wall(dir.path, 4);
  fs::path log = dir.path / "wall.log";
  const std::string args =
      gridConfig(dir.path) + " builtin:animated --nodes " + wall.addresses() + " --frames 2 --size 48x40 --output ";
  ASSERT_EQ(runWall(args + (dir.path / "wall.exr").string() + " --workload beside", log), 0) << slurp(log);
  const std::string out = slurp(log);
  EXPECT_NE(out.find("workload: balance"), std::string::npos) << out;
  EXPECT_NE(out.find("screen 3  480 px"), std::string::npos) << out;
  const med::FrameBuffer workload = med::readImage((dir.path / "wall.workload.exr").string());
  const auto rects = wallLayout(48, 40, 2, 2, 0);
  for (std::size_t i = 0; i < 4; ++i)
    for (std::uint32_t y = rects[i].y0; y < rects[i].y1; ++y)
      for (std::uint32_t x = rects[i].x0; x < rects[i].x1; ++x)
        ASSERT_EQ(nodeShown(workload.colour[workload.index(x, y)], 4), i) << "screen " << i << " at " << x << "," << y;
  const med::FrameBuffer frame = med::readImage((dir.path / "wall.exr").string());
  ASSERT_EQ(runWall(args + (dir.path / "over.exr").string() + " --workload over", log), 0) << slurp(log);
  // The same frame again (a fixed seed), the workload drawn half over it:
  // what is left after taking half the frame away is each screen's colour
  // (shaded by this run's times).
  const med::FrameBuffer over = med::readImage((dir.path / "over.exr").string());
  for (std::size_t i = 0; i < 4; ++i)
    for (std::uint32_t y = rects[i].y0; y < rects[i].y1; y += 3)
      for (std::uint32_t x = rects[i].x0; x < rects[i].x1; x += 3) {
        const std::size_t at = frame.index(x, y);
        const glm::vec4 drawn(2.0f * glm::vec3(over.colour[at]) - glm::vec3(frame.colour[at]), 1.0f);
        ASSERT_EQ(nodeShown(drawn, 4), i) << "screen " << i << " at " << x << "," << y;
      }
}

// Liveness, not a stopwatch: with one node killed the others keep
// presenting (their frame numbers advance) and its screen is marked; the
// node restarted on its address presents again.
// A config that names no filter gets the path tracer's filtered preview,
// and the wall says so.
TEST(WallCli, OpensWithTheFilteredPreview) {
  TempDir dir;
  Wall wall(dir.path, 4);
  fs::path log = dir.path / "wall.log";
  ASSERT_EQ(runWall(gridConfig(dir.path, kParametersWithDefaultFilter) + " builtin:animated --nodes " +
                        wall.addresses() + " --frames 3 --size 48x40",
                    log),
            0)
      << slurp(log);
  const std::string out = slurp(log);
  EXPECT_NE(out.find("path tracer preview filter: pixel"), std::string::npos) << out;
  med::FrameBuffer unfiltered = localFrame(2, 48, 40);
  auto rects = wallLayout(48, 40, 2, 2, 0);
  for (int wait = 0; wait < 200 && wall.newestFrame(0) < 3; ++wait) std::this_thread::sleep_for(20ms);
  ASSERT_EQ(wall.newestFrame(0), 3u);
  const med::FrameBuffer tile = wall.tile(0, 3, rects[0]);
  double difference = 0;
  for (std::uint32_t y = 0; y < tile.height; ++y)
    for (std::uint32_t x = 0; x < tile.width; ++x)
      difference += std::abs(tile.colour[tile.index(x, y)].r -
                             unfiltered.colour[unfiltered.index(rects[0].x0 + x, rects[0].y0 + y)].r);
  EXPECT_GT(difference, 0.0) << "the tile is filtered, not the unfiltered render";
}

TEST(WallCli, KilledNodeIsMarkedWhileTheOthersPresentAndIsTakenBack) {
  TempDir dir;
  Wall wall(dir.path, 4);
  fs::path log = dir.path / "wall.log";
  WallProcess player(gridConfig(dir.path) + " builtin:animated --nodes " + wall.addresses() +
                         " --size 48x40 --spp 1 --max-fps 20 --status-every 0.2",
                     log);
  auto waitFor = [&](auto condition) {
    for (int i = 0; i < 600 && !condition(); ++i) std::this_thread::sleep_for(50ms);
    return condition();
  };
  ASSERT_TRUE(waitFor([&] { return wall.newestFrame(3) >= 2; })) << slurp(log);
  std::string address = wall.nodes[3]->text();
  wall.nodes[3]->kill();
  std::uint64_t killedAt = wall.newestFrame(3);
  std::uint64_t othersAt = wall.newestFrame(0);
  ASSERT_TRUE(waitFor([&] { return slurp(log).find("tile(s) marked offline") != std::string::npos; })) << slurp(log);
  ASSERT_TRUE(waitFor([&] { return wall.newestFrame(0) >= othersAt + 5 && wall.newestFrame(1) >= othersAt + 5; }))
      << "the others keep presenting\n"
      << slurp(log);
  EXPECT_EQ(wall.newestFrame(3), killedAt);
  std::string out = slurp(log);
  EXPECT_NE(out.find("node " + address + " dropped out"), std::string::npos) << out;
  EXPECT_NE(out.find("screen 3 marked offline"), std::string::npos) << out;

  wall.nodes[3] = std::make_unique<NodeProcess>(wall.args(3), address);
  ASSERT_TRUE(waitFor([&] { return wall.newestFrame(3) > killedAt; })) << "taken back\n" << slurp(log);
  EXPECT_NE(slurp(log).find("node " + address + " is back on screen 3"), std::string::npos) << slurp(log);
  EXPECT_GT(wall.newestFrame(0), othersAt + 5);
  EXPECT_EQ(player.interruptAndWait(), 0) << slurp(log);
}

// Screens of different sizes, one with a negative bezel (projector overlap
// into two neighbours), one with mullions: each shows exactly its pixels of
// the local render, and pixels behind the bezels belong to no screen.
TEST(WallCli, NonUniformWallStitchesToTheLocalRender) {
  TempDir dir;
  Wall wall(dir.path, 4);
  std::string json = std::string(R"({"mode": "tiled", "backend": "embree", )") + kParameters + R"(, "nodes": [)";
  for (int i = 0; i < 4; ++i) json += std::string(i ? "," : "") + R"({"address": "127.0.0.1:1"})";
  json += R"(], "wall": {"frame": [96, 80], "screens": [
      {"rect": [0, 0, 60, 48], "bezel": 4},
      {"rect": [60, 0, 36, 32]},
      {"rect": [60, 32, 36, 48], "bezel": -6, "window": {"position": [1920, 0], "size": [640, 480]}},
      {"rect": [0, 48, 60, 32], "bezel": 2}]}})";
  fs::path config = dir.path / "screens.json";
  std::ofstream(config) << json;
  fs::path log = dir.path / "wall.log";
  // Rendered at half the frame's size: rectangles and bezels scale with it.
  ASSERT_EQ(runWall(config.string() + " builtin:animated --nodes " + wall.addresses() +
                        " --frames 2 --size 48x40 --output " + (dir.path / "wall.exr").string(),
                    log),
            0)
      << slurp(log);
  med::FrameBuffer ref = localFrame(1, 48, 40);
  const std::vector<med::PixelRect> rects = {{2, 2, 28, 22}, {30, 0, 48, 16}, {27, 13, 48, 40}, {1, 25, 29, 39}};
  for (std::size_t i = 0; i < 4; ++i) {
    for (int wait = 0; wait < 200 && wall.newestFrame(i) < 2; ++wait) std::this_thread::sleep_for(20ms);
    ASSERT_EQ(wall.newestFrame(i), 2u) << "node " << i;
    expectTileEquals(wall.tile(i, 2, rects[i]), ref, rects[i], "screen " + std::to_string(i));
  }
  med::FrameBuffer stitched = med::readImage((dir.path / "wall.exr").string());
  for (const auto& r : rects) expectTileEquals(stitched, ref, r, "stitched");
  EXPECT_EQ(stitched.colour[stitched.index(0, 0)], glm::vec4(0.0f)) << "behind a bezel: no screen shows it";
  EXPECT_EQ(stitched.colour[stitched.index(0, 39)], glm::vec4(0.0f));
}

#ifdef TSR_MPIRUN
// The same wall started the way a cluster starts it: mpirun places the
// client (rank 0, tessera-wall) and four nodes presenting to files, which
// meet through a rendezvous folder (tessera-launch).
TEST(WallCli, MpirunStartsTheWallOnLoopback) {
  TempDir dir;
  const fs::path present = dir.path / "present", meet = dir.path / "meet", out = dir.path / "wall.exr";
  fs::create_directories(present);
  fs::create_directories(meet);
  const std::string command = std::string(TSR_MPIRUN) + " --allow-run-as-root --oversubscribe -np 5 " +
                              TSR_LAUNCH_BINARY + " --rendezvous " + meet.string() +
                              " --threads 1 --node-arg=--present --node-arg=files:" + present.string() + " -- " +
                              TSR_WALL_BINARY + " " + gridConfig(dir.path) +
                              " builtin:animated --frames 2 --size 48x40 --output " + out.string();
  const fs::path log = dir.path / "mpirun.log";
  const int raw = std::system((command + " > '" + log.string() + "' 2>&1").c_str());
  ASSERT_TRUE(WIFEXITED(raw) && WEXITSTATUS(raw) == 0) << slurp(log);
  EXPECT_NE(slurp(log).find("4 of 4 nodes online"), std::string::npos) << slurp(log);
  const med::FrameBuffer ref = localFrame(1, 48, 40);
  expectTileEquals(med::readImage(out.string()), ref, {0, 0, 48, 40}, "the stitched frame");
  // Ranks 1..4 are the screens in rank order; each presented its part of frame 2.
  auto rects = wallLayout(48, 40, 2, 2, 0);
  for (std::size_t i = 0; i < 4; ++i) {
    const fs::path tile = present / ("rank-" + std::to_string(i + 1) + "-frame2-" + std::to_string(rects[i].x0) + "-" +
                                     std::to_string(rects[i].y0) + ".exr");
    ASSERT_TRUE(fs::exists(tile)) << tile << "\n" << slurp(log);
    expectTileEquals(med::readImage(tile.string()), ref, rects[i], "rank " + std::to_string(i + 1));
  }
}
#endif

}  // namespace
}  // namespace tsr::cluster::test
