#pragma once
// tessera-viewer --script: one action a line, run one per frame (waits span
// frames). Blank lines and lines starting with # are skipped. The whole file
// is parsed and checked before the window opens:
//
//   backend VIEWPORT NAME         switch viewport VIEWPORT (0 = leftmost) to a back-end
//   orbit DEGREES                 turn the camera around its target (about the up axis)
//   tilt DEGREES                  turn it up or down
//   pan DX DY                     move camera and target by fractions of the view's height
//   zoom FACTOR                   distance to the target times FACTOR (0.5: twice as near)
//   wait frames N                 let N frames pass
//   wait samples N                until every path-traced viewport has N samples a pixel
//                                 (or its sample limit)
//   param VIEWPORT NAME=VALUE     set a back-end parameter of one viewport
//   limit N                       the path tracer's sample limit
//   pause | resume                stop or continue path tracing
//   raster-while-moving on|off    figure 5.6's option
//   workload on|off               with --cluster: which node rendered which tile, over viewport 0 (key O)
//   time SECONDS                  the animations' time
//   pick VIEWPORT X Y             click pixel (X, Y) of a viewport: selects the object there
//   bookmark save NAME | bookmark load NAME
//   screenshot FILE [VIEWPORT]    the viewport's image (default 0): PNG, or EXR with its AOVs as layers
//   window-screenshot FILE        the whole window, panels included (PNG)
//   open SCENE                    open another scene
//   report                        print the seconds and frames since the camera last moved and
//                                 what each viewport shows with how many samples (for benchmarks)
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace tsr::app {

class ScriptError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

struct ScriptAction {
  std::string verb;                // the first word ("wait frames" and "wait samples" become "wait-frames", ...)
  std::vector<std::string> words;  // the rest, as written
  std::uint32_t viewport = 0;      // for backend, param, pick, focus-on, screenshot
  double number = 0;               // orbit, tilt, zoom, time; pan's DX; lens' aperture; shutter's open
  double number2 = 0;              // pan's DY; pick's and focus-on's Y; lens' focus distance; shutter's close
  std::int64_t count = 0;          // wait's N, limit's N, pick's and focus-on's X
  std::string where;               // "FILE:LINE" for messages
};

struct ScriptLimits {
  std::uint32_t viewports = 1;
  std::vector<std::string> backends;  // the names the build offers
};

// Throws ScriptError "FILE:LINE: what is wrong" for the first bad line, or
// "FILE: ..." when it cannot be read or is too large (1 MiB, 100000 actions).
std::vector<ScriptAction> parseScript(const std::string& path, const ScriptLimits& limits);
std::vector<ScriptAction> parseScriptText(const std::string& text, const std::string& name, const ScriptLimits& limits);

}  // namespace tsr::app
