// tessera-wall end to end on real node processes presenting to files: the
// presented tiles stitch to one local render of the same frame; a node that
// dies leaves the others presenting with its screen marked, and is taken
// back when it returns; a wall that is not a grid stitches too.
#include <csignal>
#include <filesystem>
#include <fstream>
#include <regex>
#include <thread>

#include <gtest/gtest.h>

#include "cluster_test_util.hpp"
#include "tsr/cluster/wall_layout.hpp"
#include "tsr/med/embree/register.hpp"
#include "tsr/med/image_file.hpp"
#include "tsr/med/viewport_registry.hpp"
#include "tsr/sg/replica.hpp"

namespace tsr::cluster::test {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

struct TempDir {
  fs::path path;
  TempDir() {
    char name[] = "/tmp/tsr-wall-XXXXXX";
    path = mkdtemp(name);
  }
  ~TempDir() { fs::remove_all(path); }
};

med::Parameters pathTracer() {
  med::Parameters p;
  p.set("spp", std::int64_t{2});
  p.set("maxDepth", std::int64_t{3});
  p.set("seed", std::int64_t{5});
  p.set("threads", std::int64_t{1});
  return p;
}

const char* kParameters = R"("parameters": {"spp": 2, "maxDepth": 3, "seed": 5, "threads": 1})";

std::string gridConfig(const fs::path& dir) {
  std::string json = std::string(R"({"mode": "tiled", "backend": "embree", )") + kParameters + R"(, "nodes": [)";
  for (int i = 0; i < 4; ++i) json += std::string(i ? "," : "") + R"({"address": "127.0.0.1:1"})";
  json += R"(], "wall": {"columns": 2, "rows": 2},
    "timeouts": {"heartbeatMs": 100, "deadAfterMs": 1000, "retryMs": 200, "connectMs": 3000}})";
  fs::path p = dir / "wall.json";
  std::ofstream(p) << json;
  return p.string();
}

struct Wall {
  std::vector<std::unique_ptr<NodeProcess>> nodes;
  fs::path present;
  explicit Wall(const fs::path& dir, std::size_t count) : present(dir / "present") {
    fs::create_directories(present);
    for (std::size_t i = 0; i < count; ++i) nodes.push_back(std::make_unique<NodeProcess>(args(i)));
  }
  std::vector<std::string> args(std::size_t i) const {
    return {"--present", "files:" + present.string(), "--name", "n" + std::to_string(i)};
  }
  std::string addresses() const {
    std::string out;
    for (const auto& n : nodes) out += (out.empty() ? "" : ",") + n->text();
    return out;
  }
  // The newest frame node i presented, 0 if none.
  std::uint64_t newestFrame(std::size_t i) const {
    std::regex name("n" + std::to_string(i) + R"(-frame(\d+)-\d+-\d+\.exr)");
    std::uint64_t newest = 0;
    for (const auto& e : fs::directory_iterator(present)) {
      std::smatch m;
      std::string file = e.path().filename().string();
      if (std::regex_match(file, m, name)) newest = std::max<std::uint64_t>(newest, std::stoull(m[1]));
    }
    return newest;
  }
  med::FrameBuffer tile(std::size_t i, std::uint64_t frame, const med::PixelRect& r) const {
    return med::readImage((present / ("n" + std::to_string(i) + "-frame" + std::to_string(frame) + "-" +
                                      std::to_string(r.x0) + "-" + std::to_string(r.y0) + ".exr"))
                              .string());
  }
};

// tessera-wall in the background, its stdout into a file.
class WallProcess {
 public:
  WallProcess(const std::string& args, const fs::path& log) {
    pid_ = fork();
    if (pid_ == 0) {
      std::string command = std::string("exec ") + TSR_WALL_BINARY + " " + args + " > '" + log.string() + "' 2>&1";
      execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
  }
  ~WallProcess() {
    if (pid_ > 0) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
  }
  int interruptAndWait() {
    kill(pid_, SIGINT);
    int status = 0;
    waitpid(pid_, &status, 0);
    pid_ = -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
 private:
  pid_t pid_ = -1;
};

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  return {std::istreambuf_iterator<char>(in), {}};
}

int runWall(const std::string& args, const fs::path& log) {
  std::string command = std::string(TSR_WALL_BINARY) + " " + args + " > '" + log.string() + "' 2>&1";
  int raw = std::system(command.c_str());
  return WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
}

// The local render of builtin:animated at frame `frame` of 24 fps.
med::FrameBuffer localFrame(int frame, std::uint32_t width, std::uint32_t height) {
  AnimatedScene s("builtin:animated");
  s.pose(frame);
  sg::Replica replica;
  replica.apply(s.scene.commit());
  med::ViewportRegistry registry;
  med::registerEmbree(registry);
  med::ContextPool contexts;
  auto local = registry.create({"embree", s.imported.root, s.imported.background, pathTracer(), true}, contexts);
  med::FrameBuffer fb;
  local->render(replica, med::View::fromCamera(*s.scene.find<sg::Camera>(s.imported.cameras.front()), width, height), fb);
  return fb;
}

// `tile` (r's size, or a whole frame) shows ref's pixels of r.
void expectTileEquals(const med::FrameBuffer& tile, const med::FrameBuffer& ref, const med::PixelRect& r, const std::string& what) {
  bool whole = tile.width == ref.width && tile.height == ref.height;
  ASSERT_TRUE(whole || (tile.width == r.width() && tile.height == r.height())) << what;
  for (std::uint32_t y = r.y0; y < r.y1; ++y)
    for (std::uint32_t x = r.x0; x < r.x1; ++x) {
      std::size_t at = whole ? tile.index(x, y) : tile.index(x - r.x0, y - r.y0);
      ASSERT_EQ(tile.colour[at], ref.colour[ref.index(x, y)]) << what << " at " << x << "," << y;
    }
}

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

// Liveness, not a stopwatch: with one node killed the others keep
// presenting (their frame numbers advance) and its screen is marked; the
// node restarted on its address presents again.
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
      << "the others keep presenting\n" << slurp(log);
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
  ASSERT_EQ(runWall(config.string() + " builtin:animated --nodes " + wall.addresses() + " --frames 2 --size 48x40 --output " +
                        (dir.path / "wall.exr").string(),
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

}  // namespace
}  // namespace tsr::cluster::test
