// tessera-viewer's inputs, without a window: the command line, scripts and
// bookmark files are checked before anything opens.
#include <fstream>

#include "camera_bookmarks.hpp"
#include "command_runner.hpp"
#include "viewer_script.hpp"

namespace {

using ::testing::HasSubstr;
using tsr::test::Outcome;

class ViewerCommand : public tsr::test::CommandTest {
 protected:
  Outcome run(const std::string& args) { return runBinary(TSR_VIEWER_PATH, args); }
};

TEST_F(ViewerCommand, HelpListsEveryOptionAndKey) {
  const Outcome r = run("--help");
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* option : {"--viewports", "--size", "--spp", "--max-depth", "--threads", "--param",
                             "--raster-while-moving", "--script", "--exit-after", "--hide-panels", "--validate",
                             "--cluster", "--nodes", "--token-file", "--max-file-mb", "--max-elements"})
    EXPECT_THAT(r.out, HasSubstr(option));
  for (const char* key : {"left drag", "right drag", "wheel", "W A S D", "F12", "Space", "cycle the back-end", "Drop"})
    EXPECT_THAT(r.out, HasSubstr(key));
}

TEST_F(ViewerCommand, BadScriptLineIsAnErrorNamingFileAndLine) {
  std::ofstream(dir / "bad.txt") << "wait frames 2\n\norbit sideways\n";
  const Outcome r = run("builtin:cornell --script bad.txt --exit-after");
  EXPECT_EQ(r.status, 2);
  EXPECT_THAT(r.err, HasSubstr("error: bad.txt:3: degrees 'sideways' is not a number"));
}

TEST_F(ViewerCommand, ASettingGivenTwiceIsRefused) {
  for (const auto& [args, message] :
       {std::pair{"--max-depth 2 --param maxDepth=3", "--max-depth and --param maxDepth both set 'maxDepth'"},
        std::pair{"--param seed=1 --param seed=2", "--param seed=2: 'seed' is given twice"}}) {
    const Outcome r = run(std::string("builtin:cornell ") + args);
    EXPECT_EQ(r.status, 2) << args;
    EXPECT_THAT(r.err, HasSubstr(message)) << args;
  }
}

TEST_F(ViewerCommand, UsageErrorsExitWithTwo) {
  for (const char* args : {"--viewports embree,,vulkan", "--viewports raytracer", "--size 0x10", "--exit-after",
                           "--script missing.txt", "builtin:nothing", "--spp 0"}) {
    const Outcome r = run(std::string("builtin:cornell ") + args);
    EXPECT_EQ(r.status, 2) << args;
    EXPECT_THAT(r.err, HasSubstr("error: ")) << args;
  }
}

tsr::app::ScriptLimits limits() { return {2, {"coverage", "embree", "vulkan"}}; }

TEST(ViewerScript, ParsesEveryAction) {
  const auto actions = tsr::app::parseScriptText(
      "# comment\nbackend 1 vulkan\norbit -30\ntilt 5\npan 0.1 -0.2\nzoom 0.5\nwait frames 3\nwait samples 64\n"
      "param 0 filter=pixel\nlimit 256\npause\nresume\nraster-while-moving on\ntime 1.5\npick 1 10 20\n"
      "bookmark save a\nbookmark load a\nscreenshot a.png 1\nwindow-screenshot w.png\nopen builtin:cornell\n"
      "workload on\nlens 0.1 3\nfocus-on 1 10 20\nshutter 0.25 0.5\n",
      "s.txt", limits());
  ASSERT_EQ(actions.size(), 23u);
  EXPECT_EQ(actions[0].verb, "backend");
  EXPECT_EQ(actions[0].viewport, 1u);
  EXPECT_EQ(actions[1].number, -30);
  EXPECT_EQ(actions[5].verb, "wait-frames");
  EXPECT_EQ(actions[5].count, 3);
  EXPECT_EQ(actions[6].verb, "wait-samples");
  EXPECT_EQ(actions[13].count, 10);
  EXPECT_EQ(actions[13].number2, 20);
  EXPECT_EQ(actions[16].viewport, 1u);
  EXPECT_EQ(actions[0].where, "s.txt:2");
  EXPECT_EQ(actions[19].verb, "workload");
  EXPECT_EQ(actions[19].count, 1);
  EXPECT_EQ(actions[20].number, 0.1);
  EXPECT_EQ(actions[20].number2, 3);
  EXPECT_EQ(actions[21].viewport, 1u);
  EXPECT_EQ(actions[21].count, 10);
  EXPECT_EQ(actions[21].number2, 20);
  EXPECT_EQ(actions[22].verb, "shutter");
  EXPECT_EQ(actions[22].number, 0.25);
  EXPECT_EQ(actions[22].number2, 0.5);
}

TEST(ViewerScript, RefusesBadLinesWithTheirLocation) {
  const std::vector<std::pair<std::string, std::string>> cases{
      {"backend 2 vulkan", "s.txt:1: viewport 2 is outside 0 .. 1"},
      {"backend 0 optix", "unknown back-end 'optix'"},
      {"orbit", "usage: orbit DEGREES"},
      {"orbit nan", "is not a number"},
      {"zoom 0", "factor 0 is outside"},
      {"wait hours 3", "wait what?"},
      {"wait frames -1", "frames -1 is outside"},
      {"param 0 novalue", "expected NAME=VALUE"},
      {"raster-while-moving maybe", "expected on or off"},
      {"workload maybe", "expected on or off"},
      {"shutter 0.5 0.25", "shutter close 0.25 is outside"},
      {"shutter 0 2", "shutter close 2 is outside"},
      {"dance", "unknown action 'dance'"},
      {"screenshot", "usage: screenshot FILE [VIEWPORT]"},
  };
  for (const auto& [line, message] : cases) {
    try {
      tsr::app::parseScriptText(line + "\n", "s.txt", limits());
      ADD_FAILURE() << line << " was accepted";
    } catch (const tsr::app::ScriptError& e) {
      EXPECT_THAT(e.what(), HasSubstr(message)) << line;
    }
  }
  EXPECT_THROW(tsr::app::parseScriptText(std::string("orbit 1\0x", 9), "s.txt", limits()), tsr::app::ScriptError);
}

TEST(CameraBookmarks, RoundTripAndValidation) {
  tsr::app::Bookmark b{"door", {1, 2, 3}, 4.5f, 30, -10};
  const auto text = tsr::app::formatBookmarks({b});
  const auto back = tsr::app::parseBookmarks(text, "b.json");
  ASSERT_EQ(back.size(), 1u);
  EXPECT_EQ(back[0].name, "door");
  EXPECT_EQ(back[0].target, glm::vec3(1, 2, 3));
  EXPECT_FLOAT_EQ(back[0].distance, 4.5f);
  EXPECT_FLOAT_EQ(back[0].pitch, -10.0f);
  for (const char* bad :
       {"[1]", "{\"version\": 2, \"bookmarks\": []}", "{\"version\": 1}",
        R"({"version": 1, "bookmarks": [{"name": "", "target": [0,0,0], "distance": 1, "yaw": 0, "pitch": 0}]})",
        R"({"version": 1, "bookmarks": [{"name": "a", "target": [0,0], "distance": 1, "yaw": 0, "pitch": 0}]})",
        R"({"version": 1, "bookmarks": [{"name": "a", "target": [0,0,0], "distance": -1, "yaw": 0, "pitch": 0}]})",
        R"({"version": 1, "bookmarks": [{"name": "a", "target": [0,0,0], "distance": 1, "yaw": 0, "pitch": 91}]})",
        R"({"version": 1, "bookmarks": [{"name": "a", "target": [0,0,0], "distance": 1, "yaw": 0}]})", "{"})
    EXPECT_THROW(tsr::app::parseBookmarks(bad, "b.json"), tsr::app::BookmarkError) << bad;
}

TEST(CameraBookmarks, ABadFileLeavesTheListAsItWas) {
  const auto dir = std::filesystem::temp_directory_path() / ("tsr_marks_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  tsr::app::BookmarkFile file;
  file.load((dir / "s.gltf.bookmarks.json").string());  // none yet: empty
  EXPECT_TRUE(file.bookmarks.empty());
  file.save({"a", {0, 0, 0}, 1, 0, 0});
  tsr::app::BookmarkFile reread;
  reread.load(file.path);
  ASSERT_EQ(reread.bookmarks.size(), 1u);
  std::ofstream(dir / "broken.json") << "{\"version\": 1, \"bookmarks\": [";
  EXPECT_THROW(reread.load((dir / "broken.json").string()), tsr::app::BookmarkError);
  EXPECT_EQ(reread.bookmarks.size(), 1u);
  EXPECT_EQ(reread.path, file.path);
  EXPECT_EQ(tsr::app::BookmarkFile::pathFor("builtin:instances:4"), "builtin-instances-4.bookmarks.json");
  EXPECT_EQ(tsr::app::BookmarkFile::pathFor("/x/a.glb"), "/x/a.glb.bookmarks.json");
  std::filesystem::remove_all(dir);
}

}  // namespace
