#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

struct Outcome {
  int status = -1;
  std::string out;
  std::string err;
};

class InspectCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    std::random_device rd;
    dir = fs::temp_directory_path() / ("tsr_inspect_" + std::to_string(rd()));
    fs::create_directories(dir);
  }
  void TearDown() override { fs::remove_all(dir); }

  static std::string slurp(const fs::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }

  Outcome run(const std::string& args) {
    const fs::path out = dir / "out.txt", err = dir / "err.txt";
    const std::string cmd =
        std::string("'") + TSR_INSPECT_PATH + "' " + args + " > '" + out.string() + "' 2> '" + err.string() + "'";
    const int raw = std::system(cmd.c_str());
    Outcome r;
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    r.out = slurp(out);
    r.err = slurp(err);
    return r;
  }

  static void expectOneErrorLine(const Outcome& r, const std::string& about) {
    EXPECT_EQ(r.status, 2);
    ASSERT_FALSE(r.err.empty());
    EXPECT_EQ(r.err.rfind("error: ", 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(r.err.back(), '\n');
    EXPECT_THAT(r.err, HasSubstr(about));
  }

  fs::path dir;
};

TEST_F(InspectCommand, PrintsCountsOfTheCornellBox) {
  const Outcome r = run("builtin:cornell");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("Geometry: 6"));
  EXPECT_THAT(r.out, HasSubstr("Camera: 1"));
  EXPECT_THAT(r.out, HasSubstr("cameras: 1"));
  EXPECT_THAT(r.out, HasSubstr("animations: 0"));
  EXPECT_THAT(r.out, HasSubstr("triangles: "));
  EXPECT_THAT(r.out, HasSubstr("bounds: (0, 0, 0) - (556, 548.8, 559.2)"));
  EXPECT_TRUE(r.err.empty()) << r.err;
}

TEST_F(InspectCommand, PrintsJson) {
  const Outcome r = run("builtin:instances:25 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["scene"], "builtin:instances:25");
  EXPECT_EQ(j["geometryInstances"], 25);
  EXPECT_GT(j["triangles"].get<std::uint64_t>(), j["uniqueTriangles"].get<std::uint64_t>());
  EXPECT_EQ(j["lights"], 1);
  EXPECT_EQ(j["cameras"], 1);
  EXPECT_EQ(j["animations"], 0);
  EXPECT_EQ(j["containersByType"]["Transform"], 27);
  EXPECT_EQ(j["bounds"]["min"].size(), 3u);
  EXPECT_LT(j["bounds"]["min"][0].get<double>(), j["bounds"]["max"][0].get<double>());

  const Outcome a = run("builtin:animated --json");
  ASSERT_EQ(a.status, 0) << a.err;
  EXPECT_EQ(nlohmann::json::parse(a.out)["animations"], 1);
  EXPECT_EQ(nlohmann::json::parse(a.out)["animationDuration"], 4.0);
}

TEST_F(InspectCommand, MalformedFileIsOneErrorLine) {
  const fs::path bad = dir / "bad.gltf";
  std::ofstream(bad) << R"({"asset": {"version": "2.0"}, "nodes": [{"children": [0]}]})";
  expectOneErrorLine(run("'" + bad.string() + "'"), bad.string() + ": node 0 is its own child");
  const fs::path text = dir / "text.gltf";
  std::ofstream(text) << "not json\nat all\n";
  expectOneErrorLine(run("'" + text.string() + "'"), "invalid JSON");
}

TEST_F(InspectCommand, MissingFileAndBadUsageExitWithTwo) {
  const fs::path missing = dir / "missing.glb";
  expectOneErrorLine(run("'" + missing.string() + "'"), missing.string());
  EXPECT_EQ(run("").status, 2);
  EXPECT_EQ(run("builtin:cornell --no-such-flag").status, 2);
  expectOneErrorLine(run("builtin:nope --json"), "builtin:nope: unknown built-in scene");
}

}  // namespace
