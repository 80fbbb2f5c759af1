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

const std::string kGoodImage = "a good image from an earlier run";

class BadInput : public tsr::test::CommandTest {
 protected:
  // A case refused with a good out.png already there: one "error:" line
  // naming `about`, out.png as it was, and no temporary file beside it.
  Outcome expectRefusedKeepingImage(const std::string& binary, const std::string& args, const std::string& about,
                                    const std::string& env = "") {
    std::ofstream(dir / "out.png") << kGoodImage;
    Outcome r = run(binary, args, env);
    expectOneErrorLine(r, about);
    EXPECT_EQ(slurp(dir / "out.png"), kGoodImage);
    EXPECT_TRUE(temporaries().empty());
    return r;
  }
  // `env` sets or (-u NAME) removes environment variables for this run only.
  Outcome run(const std::string& binary, const std::string& args, const std::string& env = "") {
    return runBinary("/usr/bin/env", env + " /usr/bin/timeout 60 '" + binary + "' " + args);
  }
  // Names of files in the scratch folder that the run must not leave behind.
  std::vector<std::string> temporaries() const {
    std::vector<std::string> found;
    for (const auto& e : fs::directory_iterator(dir))
      if (e.path().filename().string().find(".tmp-") != std::string::npos) found.push_back(e.path().filename());
    return found;
  }
};

// The viewer and the anaglyph window check everything they read before a
// window opens: without a display, a case that got as far as the window
// would fail with "cannot open a window" instead of naming its problem.
const std::string kNoDisplay = "-u DISPLAY -u WAYLAND_DISPLAY";

// One bad option and what its error line must name.
struct OptionCase {
  std::string args, about;
};

// Image sizes every program that renders refuses, followed by `own`.
std::vector<OptionCase> impossibleSizesAnd(std::vector<OptionCase> own) {
  std::vector<OptionCase> cases = {
      {"--size 0x0", "--size 0x0"},
      {"--size 100000x100000", "--size 100000x100000"},
      {"--size 20000x20000", "pixels"},
  };
  cases.insert(cases.end(), own.begin(), own.end());
  return cases;
}

// Config files no cluster client accepts, and the phrase naming each.
struct BadConfig {
  std::string file, about;
};
std::vector<BadConfig> writeBadConfigs(const fs::path& dir) {
  std::ofstream(dir / "bad.json") << R"({"mode": "cooperative", "nodes": [)";
  std::ofstream(dir / "wrong-type.json") << R"({"mode": 7, "nodes": [{"address": "127.0.0.1:1"}]})";
  std::ofstream(dir / "empty.json") << "";
  return {{"bad.json", "bad.json"},
          {"wrong-type.json", "mode"},
          {"empty.json", "empty.json"},
          {"missing.json", "missing.json"}};
}

TEST_F(BadInput, RenderRefusesEveryBadSceneAndKeepsTheOldImage) {
  for (const auto& input : tsr::test::writeBadSceneInputs(dir)) {
    SCOPED_TRACE(input.name);
    expectRefusedKeepingImage(TSR_RENDER_PATH, "'" + input.path + "' --size 16x16 --spp 1 --quiet --output out.png",
                              input.about);
  }
}

TEST_F(BadInput, InspectRefusesEveryBadScene) {
  for (const auto& input : tsr::test::writeBadSceneInputs(dir)) {
    SCOPED_TRACE(input.name);
    expectOneErrorLine(run(TSR_INSPECT_PATH, "'" + input.path + "'"), input.about);
  }
}

TEST_F(BadInput, RenderRefusesBadOptionsAndConfigs) {
  std::vector<OptionCase> cases = impossibleSizesAnd({
      {"--size 16", "expected WxH"},
      {"--backend nosuch", "nosuch"},
      {"--output out.unknownformat", "out.unknownformat"},
      {"--output ''", "--output: an empty file name"},
      {"--stats-json ''", "--stats-json: an empty file name"},
  });
  for (const auto& config : writeBadConfigs(dir))
    cases.push_back({"--cluster " + config.file + " --nodes 127.0.0.1:1", config.about});
  for (const auto& c : cases) {
    SCOPED_TRACE(c.args);
    const std::string output = c.args.find("--output") == std::string::npos ? " --output out.png" : "";
    expectRefusedKeepingImage(TSR_RENDER_PATH, "builtin:cornell --spp 1 --quiet " + c.args + output, c.about);
    EXPECT_FALSE(fs::exists(dir / "out.unknownformat"));
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
      {"--token-file ''", "an empty file name"},
      {"--present bogus", "--present"},
      {"--present files:missing-folder", "missing-folder"},
      {"--no-such-option", "--no-such-option"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.args);
    const Outcome r = run(TSR_NODE_PATH, c.args);
    expectOneErrorLine(r, c.about);
    EXPECT_EQ(r.out.find("listening on"), std::string::npos);
  }
}

#ifdef TSR_WALL_PATH
// tessera-wall checks its config, options and scene before it contacts a
// node (the config's one node does not exist) and writes no --output.
TEST_F(BadInput, WallRefusesBadScenesConfigsAndOptions) {
  std::ofstream(dir / "wall.json") << R"({"mode": "tiled", "backend": "embree", "nodes": [{"address": "127.0.0.1:1"}],
    "wall": {"columns": 1, "rows": 1}, "timeouts": {"connectMs": 200}})";
  std::ofstream(dir / "coop.json") << R"({"mode": "cooperative", "nodes": [{"address": "127.0.0.1:1"}]})";
  std::vector<OptionCase> cases = {
      {"coop.json builtin:cornell", "a wall needs \"mode\": \"tiled\""},
      {"wall.json builtin:cornell --size 0x0", "--size 0x0"},
      {"wall.json builtin:cornell --size 100000x100000", "--size 100000x100000"},
      {"wall.json builtin:cornell --fps nan", "--fps"},
      {"wall.json builtin:cornell --max-fps -1", "--max-fps"},
      {"wall.json builtin:cornell --status-every inf", "--status-every"},
      {"wall.json builtin:cornell --spp -1", "--spp"},
      {"wall.json builtin:cornell --nodes nohost", "nohost"},
      {"wall.json builtin:cornell --nodes 127.0.0.1:1,127.0.0.1:2", "needs 1 nodes"},
      {"wall.json builtin:cornell --token-file missing-token", "missing-token"},
      {"wall.json builtin:cornell --token-file ''", "an empty file name"},
      {"wall.json builtin:cornell --output ''", "an empty file name"},
      {"wall.json builtin:cornell --camera nosuch", "nosuch"},
      {"wall.json builtin:nosuch", "builtin:nosuch"},
  };
  for (const auto& config : writeBadConfigs(dir)) cases.push_back({config.file + " builtin:cornell", config.about});
  for (const auto& input : tsr::test::writeBadSceneInputs(dir))
    cases.push_back({"wall.json '" + input.path + "'", input.about});
  for (const auto& c : cases) {
    SCOPED_TRACE(c.args);
    const std::string output = c.args.find("--output") == std::string::npos ? " --output out.png" : "";
    const Outcome r = expectRefusedKeepingImage(TSR_WALL_PATH, c.args + " --frames 1" + output, c.about);
    EXPECT_EQ(r.out.find("nodes online"), std::string::npos) << "refused before connecting";
  }
}
#endif

#ifdef TSR_VIEWER_PATH
TEST_F(BadInput, ViewerRefusesEveryBadSceneBeforeOpeningAWindow) {
  for (const auto& input : tsr::test::writeBadSceneInputs(dir)) {
    SCOPED_TRACE(input.name);
    expectOneErrorLine(run(TSR_VIEWER_PATH, "'" + input.path + "' --viewports coverage", kNoDisplay), input.about);
  }
}

TEST_F(BadInput, ViewerRefusesBadOptionsScriptsAndConfigs) {
  std::vector<OptionCase> cases = impossibleSizesAnd({
      {"--size 16", "expected WxH"},
      {"--viewports nosuch", "nosuch"},
      {"--viewports coverage,,vulkan", "an empty back-end name"},
      {"--spp 0", "--spp"},
      {"--max-file-mb 0", "--max-file-mb"},
      {"--exit-after", "--exit-after needs --script"},
      {"--script ''", "--script: an empty file name"},
      {"--no-such-option", "--no-such-option"},
  });
  for (const auto& config : writeBadConfigs(dir))
    cases.push_back({"--cluster " + config.file + " --nodes 127.0.0.1:1", config.about});
  for (const auto& script : tsr::test::writeBadScriptFiles(dir))
    cases.push_back({"--script " + script.path, script.about});
  std::ofstream(dir / "nan.txt") << "orbit nan\n";
  std::ofstream(dir / "viewport.txt") << "backend 1 vulkan\n";
  std::ofstream(dir / "backend.txt") << "backend 0 nosuch\n";
  cases.push_back({"--script nan.txt", "nan.txt:1: degrees 'nan' is not a number"});
  cases.push_back({"--script viewport.txt", "viewport.txt:1: viewport 1 is outside 0 .. 0"});
  cases.push_back({"--script backend.txt", "unknown back-end 'nosuch'"});
  for (const auto& c : cases) {
    SCOPED_TRACE(c.args);
    const std::string viewports = c.args.find("--viewports") == std::string::npos ? " --viewports coverage" : "";
    expectOneErrorLine(run(TSR_VIEWER_PATH, "builtin:cornell " + c.args + viewports, kNoDisplay), c.about);
  }
}
#endif

#ifdef TSR_ANAGLYPH_PATH
TEST_F(BadInput, AnaglyphRefusesEveryBadSceneAndKeepsTheOldImage) {
  for (const auto& input : tsr::test::writeBadSceneInputs(dir)) {
    SCOPED_TRACE(input.name);
    expectRefusedKeepingImage(TSR_ANAGLYPH_PATH, "'" + input.path + "' --size 16x16 --spp 1 --output out.png",
                              input.about, kNoDisplay);
  }
}

TEST_F(BadInput, AnaglyphRefusesBadOptionsAndScripts) {
  std::vector<OptionCase> cases = impossibleSizesAnd({
      {"--backend nosuch", "nosuch"},
      {"--output out.unknownformat", "out.unknownformat"},
      {"--method nosuch", "--method"},
      {"--eye-separation nan", "--eye-separation"},
      {"--zero-parallax -1", "--zero-parallax"},
      {"--zero-parallax inf", "--zero-parallax"},
      {"--nodes 'a b:1'", "the host must be"},
      {"--nodes 127.0.0.1:1 --token-file missing-token", "missing-token"},
      {"--token-file missing-token", "--token-file needs --nodes"},
      {"--output ''", "--output: an empty file name"},
      {"--script ''", "--script: an empty file name"},
  });
  for (const auto& script : tsr::test::writeBadScriptFiles(dir))
    cases.push_back({"--script " + script.path, script.about});
  std::ofstream(dir / "nan.script") << "orbit nan 0\n";
  cases.push_back({"--script nan.script", "nan.script line 1: orbit needs a number"});
  for (const auto& c : cases) {
    SCOPED_TRACE(c.args);
    // A script needs the window, so those cases go without --output.
    const bool headless = c.args.find("--output") == std::string::npos && c.args.find("--script") == std::string::npos;
    const std::string output = headless ? " --output out.png" : "";
    const std::string size = c.args.find("--size") == std::string::npos ? " --size 16x16" : "";
    expectRefusedKeepingImage(TSR_ANAGLYPH_PATH, "builtin:cornell --spp 1 " + c.args + size + output, c.about,
                              kNoDisplay);
    EXPECT_FALSE(fs::exists(dir / "out.unknownformat"));
  }
}
#endif

// Every check tessera-launch can make alone comes before a rank waits for
// the others: a bad rendezvous, rank or program is a usage error at once,
// and nothing is left in the rendezvous folder.
TEST_F(BadInput, LaunchRefusesBadRendezvousRanksAndPrograms) {
  fs::create_directories(dir / "meet");
  std::ofstream(dir / "afile") << "not a folder";
  const std::string noLauncher = "-u SLURM_PROCID -u SLURM_NTASKS -u OMPI_COMM_WORLD_RANK -u OMPI_COMM_WORLD_SIZE ";
  const std::string folder = "--rendezvous meet --job j ";
  const struct {
    std::string env, args, about;
  } cases[] = {
      {"", "--rank 0 --size 2 --job j -- true", "give --rendezvous DIR"},
      {"", "--rendezvous nowhere --job j --rank 0 --size 2 -- true", "--rendezvous nowhere: no such folder"},
      {"", "--rendezvous afile --job j --rank 0 --size 2 -- true", "--rendezvous afile: not a folder"},
      {"", "--rendezvous meet --job ../up --rank 0 --size 2 -- true", "job name '../up'"},
      {"", "--rendezvous meet --rank 0 --size 2 -- true", "no job name"},
      {"", "--rendezvous-address nohost:notaport --rank 0 --size 2 -- true", "nohost:notaport"},
      {"", "--rendezvous-address 127.0.0.1:99999 --rank 0 --size 2 -- true", "99999"},
      {"", "--rendezvous-address 127.0.0.1:0 --rank 0 --size 2 -- true", "give a port every rank knows"},
      {"", "--rendezvous-address 'a,b:7000' --rank 1 --size 2", "the host must be"},
      {"", "--rendezvous-address 192.0.2.1:7000 --rank 0 --size 2 -- true", "cannot listen on 192.0.2.1:7000"},
      {"SLURM_PROCID=abc SLURM_NTASKS=2", folder + "-- true", "SLURM_PROCID='abc'"},
      {"SLURM_PROCID=2 SLURM_NTASKS=2", folder + "-- true", "rank 2 (from slurm) is not below the job size 2"},
      {"SLURM_PROCID=0", folder + "-- true", "SLURM_NTASKS is not set"},
      {"OMPI_COMM_WORLD_RANK=0 OMPI_COMM_WORLD_SIZE=99999", folder + "-- true", "job size 99999"},
      {"", folder + "--rank 3 --size 2 -- true", "rank 3 (from command line) is not below"},
      {"", folder + "--rank 0 -- true", "--rank and --size go together"},
      {"", folder + "--rank 0 --size 1 -- true", "a job of 1 process"},
      {"", folder + "--rank 0 --size 2", "no client command"},
      {"", folder + "--rank 0 --size 2 -- no-such-program-here", "no-such-program-here: no such program on PATH"},
      {"", folder + "--rank 0 --size 2 -- ./meet", "./meet: not an executable file"},
      {"", folder + "--rank 1 --size 2 --node-binary ./missing-node", "./missing-node: no such program"},
      {"", folder + "--rank 1 --size 2 --wait 0", "--wait"},
      {"", folder + "--rank 1 --size 2 --wait nan", "--wait"},
      {"", folder + "--rank 1 --size 2 --token-file ''", "--token-file: an empty file name"},
      {"", folder + "--rank 1 --size 2 --listen 'no host'", "--listen no host: not a host name"},
      {"", folder + "--rank 1 --size 2 --advertise 'a,b'", "--advertise a,b: not a host name"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.env + " " + c.args);
    expectOneErrorLine(run(TSR_LAUNCH_PATH, c.args, noLauncher + c.env), c.about);
    EXPECT_TRUE(fs::is_empty(dir / "meet"));
  }
}

}  // namespace
