// Bad input through every program: each case gets one "error:" line naming
// the problem and exit status 2, within a time bound (timeout(1) turns a
// hang into status 124), and a good output file already there is left as
// it was, with no temporary file beside it.
#include <fstream>

#include "bad_inputs.hpp"
#include "command_runner.hpp"

namespace {

namespace fs = std::filesystem;
using tsr::test::Outcome;

class BadInput : public tsr::test::CommandTest {
 protected:
  Outcome run(const std::string& binary, const std::string& args) {
    return runBinary("/usr/bin/timeout", "60 '" + binary + "' " + args);
  }
  // Names of files in the scratch folder that the run must not leave behind.
  std::vector<std::string> temporaries() const {
    std::vector<std::string> found;
    for (const auto& e : fs::directory_iterator(dir))
      if (e.path().filename().string().find(".tmp-") != std::string::npos) found.push_back(e.path().filename());
    return found;
  }
};

const std::string kGoodImage = "a good image from an earlier run";

TEST_F(BadInput, RenderRefusesEveryBadSceneAndKeepsTheOldImage) {
  for (const auto& input : tsr::test::writeBadSceneInputs(dir)) {
    SCOPED_TRACE(input.name);
    std::ofstream(dir / "out.png") << kGoodImage;
    const Outcome r = run(TSR_RENDER_PATH, "'" + input.scene + "' --size 16x16 --spp 1 --quiet --output out.png");
    expectOneErrorLine(r, input.about);
    EXPECT_EQ(slurp(dir / "out.png"), kGoodImage);
    EXPECT_TRUE(temporaries().empty());
  }
}

TEST_F(BadInput, InspectRefusesEveryBadScene) {
  for (const auto& input : tsr::test::writeBadSceneInputs(dir)) {
    SCOPED_TRACE(input.name);
    expectOneErrorLine(run(TSR_INSPECT_PATH, "'" + input.scene + "'"), input.about);
  }
}

TEST_F(BadInput, RenderRefusesBadOptionsAndConfigs) {
  std::ofstream(dir / "bad.json") << R"({"mode": "cooperative", "nodes": [)";
  std::ofstream(dir / "wrong-type.json") << R"({"mode": 7, "nodes": [{"address": "127.0.0.1:1"}]})";
  std::ofstream(dir / "empty.json") << "";
  const struct {
    std::string args, about;
  } cases[] = {
      {"--size 0x0", "--size 0x0"},
      {"--size 100000x100000", "--size 100000x100000"},
      {"--size 20000x20000", "pixels"},
      {"--size 16", "expected WxH"},
      {"--backend nosuch", "nosuch"},
      {"--cluster bad.json --nodes 127.0.0.1:1", "bad.json"},
      {"--cluster wrong-type.json --nodes 127.0.0.1:1", "mode"},
      {"--cluster empty.json --nodes 127.0.0.1:1", "empty.json"},
      {"--cluster missing.json --nodes 127.0.0.1:1", "missing.json"},
      {"--output out.unknownformat", "out.unknownformat"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.args);
    std::ofstream(dir / "out.png") << kGoodImage;
    const std::string output = c.args.find("--output") == std::string::npos ? " --output out.png" : "";
    expectOneErrorLine(run(TSR_RENDER_PATH, "builtin:cornell --spp 1 --quiet " + c.args + output), c.about);
    EXPECT_EQ(slurp(dir / "out.png"), kGoodImage);
    EXPECT_FALSE(fs::exists(dir / "out.unknownformat"));
    EXPECT_TRUE(temporaries().empty());
  }
}

TEST_F(BadInput, NodeRefusesBadStartUpsWithoutListening) {
  fs::create_directories(dir / "folder");
  std::ofstream(dir / "empty-token") << "";
  const struct {
    std::string args, about;
  } cases[] = {
      {"--token-file missing-token", "missing-token"},
      {"--token-file folder", "is a directory"},
      {"--token-file empty-token", "is empty"},
      {"--listen nohost:notaport", "nohost:notaport"},
      {"--listen 127.0.0.1:99999", "99999"},
      {"--listen 0.0.0.0:0", "without --token-file"},
      {"--threads -1", "--threads"},
      {"--no-such-option", "--no-such-option"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.args);
    const Outcome r = run(TSR_NODE_PATH, c.args);
    expectOneErrorLine(r, c.about);
    EXPECT_EQ(r.out.find("listening on"), std::string::npos);
  }
}

}  // namespace
