#include <fstream>

#include <nlohmann/json.hpp>

#include "command_runner.hpp"

namespace {

using ::testing::HasSubstr;
using tsr::test::Outcome;
namespace fs = std::filesystem;

class InspectCommand : public tsr::test::CommandTest {
 protected:
  Outcome run(const std::string& args) { return runBinary(TSR_INSPECT_PATH, args); }
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
