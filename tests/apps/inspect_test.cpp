#include <algorithm>
#include <array>
#include <fstream>

#include <nlohmann/json.hpp>

#include "../sanitizers/resident_scale.hpp"
#include "command_runner.hpp"
#include "tsr/sg/camera.hpp"
#include "tsr/sg/import/importer.hpp"
#include "tsr/sg/import/scene_stats.hpp"
#include "tsr/sg/node_world.hpp"
#include "tsr/sg/scene.hpp"
#include "tsr/sg/surface_material.hpp"

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

// A scene written as one .glb reads back with the same triangles (every
// instance its own mesh) and bounds: a built-in plant for other tools.
TEST_F(InspectCommand, WritesTheSceneAsAGlbThatReadsBack) {
  const Outcome w = run("builtin:instances:25 --json --write-glb scene.glb");
  ASSERT_EQ(w.status, 0) << w.err;
  const nlohmann::json original = nlohmann::json::parse(w.out);
  const Outcome r = run("scene.glb --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json back = nlohmann::json::parse(r.out);
  EXPECT_EQ(back["triangles"], original["triangles"]);
  EXPECT_EQ(back["geometryInstances"], original["geometryInstances"]);
  for (const char* end : {"min", "max"})
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(back["bounds"][end][c].get<double>(), original["bounds"][end][c].get<double>(), 1e-3) << end;
  expectOneErrorLine(run("builtin:cornell --write-glb /nonexistent-dir/x.glb"), "cannot write /nonexistent-dir/x.glb");
}

// What a built-in scene looks like survives the .glb: the camera where it
// was, the ceiling lamp's radiance beyond glTF's emissive factor of 1 (as
// KHR_materials_emissive_strength), the glass sphere's transmission; and its
// size: the box's millimetres become glTF's metres (0.556 m wide).
TEST_F(InspectCommand, AWrittenGlbKeepsTheCameraTheLampAndTheGlass) {
  ASSERT_EQ(run("builtin:cornell --write-glb cornell.glb").status, 0);
  tsr::sg::Scene builtin, written;
  const auto a = tsr::sg::importScene(builtin, "builtin:cornell", {});
  const auto b = tsr::sg::importScene(written, (dir / "cornell.glb").string(), {});
  ASSERT_EQ(a.cameras.size(), 1u);
  ASSERT_EQ(b.cameras.size(), 1u);
  const tsr::sg::Mat4 poseA = tsr::sg::cameraWorldPose(builtin, a.cameras[0]);
  const tsr::sg::Mat4 poseB = tsr::sg::cameraWorldPose(written, b.cameras[0]);
  EXPECT_FLOAT_EQ(a.metresPerUnit, 0.001f);
  EXPECT_FLOAT_EQ(b.metresPerUnit, 1.0f);
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      EXPECT_NEAR(poseA[c][r] * (c == 3 && r < 3 ? a.metresPerUnit : 1.0f), poseB[c][r], 1e-5) << c << r;
  const auto boundsA = tsr::sg::computeSceneStats(builtin, a.root),
             boundsB = tsr::sg::computeSceneStats(written, b.root);
  EXPECT_NEAR(boundsB.boundsMax.x - boundsB.boundsMin.x, 0.556, 1e-3) << "metres wide";
  EXPECT_NEAR(boundsA.boundsMax.x - boundsA.boundsMin.x, 556, 1) << "millimetres wide";
  EXPECT_NEAR(builtin.find<tsr::sg::Camera>(a.cameras[0])->verticalFov(),
              written.find<tsr::sg::Camera>(b.cameras[0])->verticalFov(), 1e-6);
  auto materials = [](const tsr::sg::Scene& scene) {
    std::vector<std::array<float, 6>> out;
    for (tsr::sg::ContainerId id : scene.ids())
      if (const auto* m = scene.find<tsr::sg::SurfaceMaterial>(id))
        out.push_back({m->emittedRadiance().r, m->emittedRadiance().g, m->emittedRadiance().b, m->transmission(),
                       m->ior(), m->roughness()});
    std::sort(out.begin(), out.end());
    return out;
  };
  const auto before = materials(builtin), after = materials(written);
  ASSERT_EQ(before.size(), after.size());
  float brightest = 0, transmission = 0;
  for (std::size_t i = 0; i < before.size(); ++i) {
    for (std::size_t k = 0; k < 6; ++k) EXPECT_NEAR(before[i][k], after[i][k], 1e-4 * (1 + before[i][k])) << i;
    brightest = std::max(brightest, after[i][0]);
    transmission = std::max(transmission, after[i][3]);
  }
  EXPECT_GT(brightest, 1.0f);  // the lamp, not clamped to glTF's factor
  EXPECT_GT(transmission, 0.0f);
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

TEST_F(InspectCommand, CameraBeyondTheCoordinateLimitIsOneErrorLine) {
  const fs::path far = writeFarCameraGltf();
  expectOneErrorLine(run("'" + far.string() + "'"), far.string() + ": node 0 translation -1e+20 is beyond 1e+12");
}

// A 300 MB .gltf of 100 million array elements took 4 GB and 17 s before it
// was refused. 20 million elements (40 MB) are refused by the scan before
// parsing: the process needs the file's bytes more than a tiny file does,
// not the 3.9 GB that parsing them takes (measured with --max-elements 3e7).
TEST_F(InspectCommand, TooManyJsonValuesAreRefusedBeforeParsing) {
  const fs::path big = dir / "big.gltf";
  {
    std::string text = R"({"asset": {"version": "2.0"}, "extras": [0)";
    text.reserve(text.size() + 40'000'000);
    for (int i = 1; i < 20'000'000; ++i) text += ",0";
    text += "]}";
    std::ofstream(big, std::ios::binary) << text;
  }
  Outcome r = run("'" + big.string() + "'");
  expectOneErrorLine(r, "the JSON holds more than 4194304 values");
  EXPECT_THAT(r.err, HasSubstr("refused before parsing"));
  EXPECT_THAT(r.err, HasSubstr("(raise it with --max-elements)"));
  const fs::path tiny = dir / "tiny.gltf";
  std::ofstream(tiny) << R"({"asset": {"version": "2.0"}})";
  const long base = peakKilobytes(TSR_INSPECT_PATH, {tiny.string()});
  const long refusing = peakKilobytes(TSR_INSPECT_PATH, {big.string()});
  ASSERT_GT(base, 0);
  EXPECT_LT(refusing - base, 100 * 1024 * tsr::test::kResidentScale)
      << "peak kilobytes: " << refusing << ", for a tiny file " << base;

  r = run("'" + big.string() + "' --max-elements 1000");
  expectOneErrorLine(r, "more than 1000 values");
  r = run("'" + big.string() + "' --max-file-mb 10");
  expectOneErrorLine(r, "more than the limit of 10485760 bytes (10 MiB)");
  EXPECT_THAT(r.err, HasSubstr("(raise it with --max-file-mb)"));
}

TEST_F(InspectCommand, ImportLimitsCanBeRaised) {
  const fs::path small = dir / "small.gltf";
  std::ofstream(small) << R"({"asset": {"version": "2.0"}, "extras": [1, 2, 3, 4, 5, 6, 7, 8, 9, 10]})";
  expectOneErrorLine(run("'" + small.string() + "' --max-elements 5"), "more than 5 values");
  EXPECT_EQ(run("'" + small.string() + "' --max-elements 50").status, 0);
}

}  // namespace
