#pragma once
// Shared by the wall tests (files and windows): real tessera-node processes
// presenting, tessera-wall as a child process, and the local render the
// screens must show.
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>

#include <gtest/gtest.h>

#include "cluster_test_util.hpp"
#include "tsr/med/embree/register.hpp"
#include "tsr/med/image_file.hpp"
#include "tsr/med/viewport_registry.hpp"
#include "tsr/sg/replica.hpp"

namespace tsr::cluster::test {

namespace fs = std::filesystem;

inline med::Parameters pathTracer() {
  med::Parameters p;
  p.set("spp", std::int64_t{2});
  p.set("maxDepth", std::int64_t{3});
  p.set("seed", std::int64_t{5});
  p.set("threads", std::int64_t{1});
  return p;
}

// The wall opens with the filtered preview; these tests compare tiles with
// an unfiltered local render, so their configs say "filter": "none" (a
// tile filtered alone is not a crop of the whole frame filtered).
inline const char* kParameters =
    R"("parameters": {"spp": 2, "maxDepth": 3, "seed": 5, "threads": 1, "filter": "none"})";
inline const char* kParametersWithDefaultFilter = R"("parameters": {"spp": 2, "maxDepth": 3, "seed": 5, "threads": 1})";

inline std::string gridConfig(const fs::path& dir, const char* parameters = kParameters) {
  std::string json = std::string(R"({"mode": "tiled", "backend": "embree", )") + parameters + R"(, "nodes": [)";
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
  bool windows;
  // Nodes presenting to files in dir/present, or (windows) in windows on the display.
  explicit Wall(const fs::path& dir, std::size_t count, bool windows = false)
      : present(dir / "present"), windows(windows) {
    fs::create_directories(present);
    for (std::size_t i = 0; i < count; ++i) nodes.push_back(std::make_unique<NodeProcess>(args(i)));
  }
  std::vector<std::string> args(std::size_t i) const {
    return {"--present", windows ? std::string("window") : "files:" + present.string(), "--name",
            "n" + std::to_string(i)};
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

inline std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  return {std::istreambuf_iterator<char>(in), {}};
}

inline int runWall(const std::string& args, const fs::path& log) {
  std::string command = std::string(TSR_WALL_BINARY) + " " + args + " > '" + log.string() + "' 2>&1";
  int raw = std::system(command.c_str());
  return WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
}

// The local render of builtin:animated at frame `frame` of 24 fps.
inline med::FrameBuffer localFrame(int frame, std::uint32_t width, std::uint32_t height, float aperture = 0.0f,
                                   float focusDistance = 5.0f, sg::Vec2 shutter = sg::Vec2(0.0f),
                                   std::int64_t seed = 5) {
  AnimatedScene s("builtin:animated");
  s.pose(frame, shutter.y > shutter.x);
  auto* lens = s.scene.find<sg::Camera>(s.imported.cameras.front());
  lens->setApertureRadius(aperture);
  lens->setFocusDistance(focusDistance);
  lens->setShutterOpen(shutter.x);
  lens->setShutterClose(shutter.y);
  sg::Replica replica;
  replica.apply(s.scene.commit());
  med::ViewportRegistry registry;
  med::registerEmbree(registry);
  med::ContextPool contexts;
  med::Parameters parameters = pathTracer();
  parameters.set("seed", seed);
  auto local = registry.create({"embree", s.imported.root, s.imported.background, parameters, true}, contexts);
  med::FrameBuffer fb;
  local->render(replica, med::View::fromCamera(*s.scene.find<sg::Camera>(s.imported.cameras.front()), width, height),
                fb);
  return fb;
}

// `tile` (r's size, or a whole frame) shows ref's pixels of r.
inline void expectTileEquals(const med::FrameBuffer& tile, const med::FrameBuffer& ref, const med::PixelRect& r,
                             const std::string& what) {
  bool whole = tile.width == ref.width && tile.height == ref.height;
  ASSERT_TRUE(whole || (tile.width == r.width() && tile.height == r.height())) << what;
  for (std::uint32_t y = r.y0; y < r.y1; ++y)
    for (std::uint32_t x = r.x0; x < r.x1; ++x) {
      std::size_t at = whole ? tile.index(x, y) : tile.index(x - r.x0, y - r.y0);
      ASSERT_EQ(tile.colour[at], ref.colour[ref.index(x, y)]) << what << " at " << x << "," << y;
    }
}

}  // namespace tsr::cluster::test
