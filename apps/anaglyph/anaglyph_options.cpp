#include "anaglyph_options.hpp"

#include "command_line.hpp"
#include "import_limit_options.hpp"
#include "preview_defaults.hpp"

#include <CLI/CLI.hpp>
#include <iostream>
#include <stdexcept>

#include "backends.hpp"
#include "option_values.hpp"
#include "parameter_option.hpp"
#include "render_job.hpp"

namespace tsr::app {

namespace {
const char* kScriptHelp = "--script FILE: one action a line, '#' starts a comment:\n"
                          "  key NAME          press a key: w a s d q e [ ] - = m r\n"
                          "  orbit DX DY       drag with the left button by DX, DY pixels\n"
                          "  pan DX DY         drag with the right button\n"
                          "  scroll N          turn the wheel N notches (positive: closer)\n"
                          "  frames N          render and present N frames\n"
                          "  screenshot FILE   write what the window shows (PNG, EXR, ...)\n";
}  // namespace

const char* methodName(med::AnaglyphMethod method) {
  return method == med::AnaglyphMethod::Dubois ? "dubois" : "red-cyan";
}

bool parseAnaglyphOptions(int argc, char** argv, AnaglyphOptions& o) {
  CLI::App app{"Red/cyan anaglyph of a scene: both eyes rendered here or on two render nodes, shown in a window or "
               "written to a file"};
  app.footer("Window keys: left drag orbit, right drag pan, wheel zoom, W/A/S/D/Q/E fly, [ ] eye separation, - = "
             "zero-parallax "
             "distance, M red-cyan/Dubois, R reset the view, Esc quit.");
  std::string size = "640x480", method = "dubois";
  std::int64_t spp = 4, maxDepth = 0, seed = 0, threads = 0;
  float separation = 0, zeroParallax = 0;
  app.add_option("scene", o.scene, sceneArgumentHelp())->required();
  app.add_option("--backend", o.backend, backendChoices() + " (here or on every node)")->capture_default_str();
  app.add_option("--size", size, "image size WxH (the window's initial size)")->capture_default_str();
  app.add_option("--spp", spp, "samples per pixel and eye")->check(CLI::Range(1, 1 << 20))->capture_default_str();
  addParameterOption(app, "--max-depth", "embree", "maxDepth", maxDepth);
  addParameterOption(app, "--seed", "embree", "seed", seed);
  addParameterOption(app, "--threads", "embree", "threads", threads);
  app.add_option("--method", method,
                 "red-cyan (red from the left eye, cyan from the right) or dubois "
                 "(least-squares projection in linear RGB: truer colours)")
      ->check(CLI::IsMember({"red-cyan", "dubois"}))
      ->capture_default_str();
  auto* sepOption = app.add_option("--eye-separation", separation,
                                   "distance between the eyes in scene units "
                                   "(default: 1/30 of the zero-parallax distance)")
                        ->check(FiniteRange(0.0, 1e6));
  auto* zpOption = app.add_option("--zero-parallax", zeroParallax,
                                  "distance of the plane that appears on the screen "
                                  "(default: to the centre of the scene's bounds)")
                       ->check(FiniteRange(1e-6, 1e9));
  std::vector<std::string> params;
  app.add_option("--param", params, "back-end parameter name=value (repeatable), e.g. filter=pixel");
  app.add_option("--nodes", o.nodes,
                 "render the left eye on the first node and the right on the second (HOST:PORT,...)");
  app.add_option("--token-file", o.tokenFile, "the nodes' shared token")->check(FileName());
  app.add_option("--output", o.output, "render one frame headless to this image file (no window)")->check(FileName());
  app.add_option("--script", o.script, "window: run the actions of this file (see --help-script), then exit")
      ->check(FileName());
  bool scriptHelp = false;
  app.add_flag("--help-script", scriptHelp, "list the actions a --script file may hold");
  ImportLimitOptions limits;
  limits.add(app, o.import);
  try {
    if (!parseCommandLine(app, argc, argv)) return false;
  } catch (const std::invalid_argument&) {
    if (scriptHelp) {  // no SCENE needed to ask
      std::cout << kScriptHelp;
      return false;
    }
    throw;
  }
  if (scriptHelp) {
    std::cout << kScriptHelp;
    return false;
  }
  parseSize(size, o.width, o.height);
  if (!o.output.empty() && !o.script.empty())
    throw std::invalid_argument("--output renders without a window; --script needs one");
  if (!o.tokenFile.empty() && o.nodes.empty()) throw std::invalid_argument("--token-file needs --nodes");
  o.method = method == "dubois" ? med::AnaglyphMethod::Dubois : med::AnaglyphMethod::RedCyan;
  if (*sepOption) o.eyeSeparation = separation;
  if (*zpOption) o.zeroParallax = zeroParallax;
  limits.apply(o.import);
  o.parameters.set("spp", spp);
  o.parameters.set("maxDepth", maxDepth);
  o.parameters.set("seed", seed);
  o.parameters.set("threads", threads);
  for (const auto& p : params) {
    auto [name, value] = med::Parameters::parse(p);
    o.parameters.set(name, value);
  }
  usePreviewDefaultsUnlessSet(o.parameters);
  return true;
}

}  // namespace tsr::app
