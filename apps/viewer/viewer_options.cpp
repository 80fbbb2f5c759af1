#include "viewer_options.hpp"

#include "command_line.hpp"
#include "import_limit_options.hpp"
#include "preview_defaults.hpp"

#include <iostream>
#include <stdexcept>

#include <CLI/CLI.hpp>

#include "option_values.hpp"
#include "parameter_option.hpp"
#include "render_job.hpp"

namespace tsr::app {

std::string viewerKeyHelp() {
  return "Keys and mouse (when the panels do not have the focus):\n"
         "  left drag      orbit around the target\n"
         "  right drag     pan (also middle drag, or shift + left drag)\n"
         "  wheel          zoom towards the target\n"
         "  click          pick the object under the mouse (coverage viewports)\n"
         "  Ctrl + click   focus the lens at what the mouse points at (panel 'Lens and shutter')\n"
         "  W A S D Q E    fly forward, left, back, right, down, up\n"
         "  F              frame the scene again\n"
         "  B              cycle the back-end of the viewport under the mouse\n"
         "  1 .. 9         select a camera bookmark\n"
         "  Space          pause / resume the path tracer\n"
         "  F12 (or P)     screenshot of every viewport (viewer-N-VIEWPORT.png in the current folder)\n"
         "  H              hide / show the panels\n"
         "  O              with --cluster: which node rendered which tile, over viewport 0 (on / off)\n"
         "  Esc            quit\n"
         "Drop a .gltf or .glb on the window to open it.\n";
}

bool parseViewerOptions(int argc, char** argv, ViewerOptions& o) {
  CLI::App app{"Look at a scene interactively, one or more viewports side by side, each with its own back-end"};
  app.footer(viewerKeyHelp());
  std::string size = "1024x576", viewports = "embree";
  std::int64_t maxDepth = 0, threads = 0, limit = o.sampleLimit;
  std::vector<std::string> params;
  app.add_option("scene", o.scene, sceneArgumentHelp() + " (default builtin:cornell)");
  app.add_option("--viewports", viewports, "back-ends of the viewports, left to right: e.g. embree,vulkan")
      ->capture_default_str();
  app.add_option("--size", size, "window size WxH")->capture_default_str();
  app.add_option("--spp", limit, "sample limit of the path tracer (it converges up to this)")
      ->check(CLI::Range(1, 1 << 20))
      ->capture_default_str();
  auto* depthOption = addParameterOption(app, "--max-depth", "embree", "maxDepth", maxDepth);
  auto* threadsOption = addParameterOption(app, "--threads", "embree", "threads", threads);
  app.add_option("--param", params, "back-end parameter name=value for every viewport (repeatable)");
  app.add_flag("--raster-while-moving", o.rasterWhileMoving,
               "path-traced viewports rasterise while the camera moves and path trace when it stops");
  app.add_option(
         "--script", o.script,
         "run the actions of FILE, one a line (backend, orbit, pan, zoom, wait, screenshot, ...: see docs/viewer.md)")
      ->check(FileName());
  app.add_flag("--exit-after", o.exitAfter, "quit when the --script is done (exit status 0)");
  app.add_flag("--hide-panels", o.hidePanels, "start with the panels hidden (H shows them)");
  app.add_flag("--validate", o.validate,
               "Vulkan validation layers on the window's device (presentation and panels); any error fails the run");
  auto* clusterGroup = app.add_option_group("Cluster", "render viewport 0 on tessera-node processes");
  clusterGroup
      ->add_option("--cluster", o.cluster,
                   "cluster config (configs/*.json): viewport 0 renders on its nodes while it shows their back-end")
      ->check(FileName());
  clusterGroup->add_option("--nodes", o.nodes, "HOST:PORT,... replacing the config's node addresses in order");
  clusterGroup->add_option("--token-file", o.tokenFile, "the nodes' shared token")->check(FileName());
  ImportLimitOptions limits;
  limits.add(app, o.import);
  if (!parseCommandLine(app, argc, argv)) return false;
  parseSize(size, o.width, o.height);
  o.sampleLimit = static_cast<std::uint32_t>(limit);
  limits.apply(o.import);
  o.viewports.clear();
  std::size_t start = 0;
  for (;;) {
    const auto comma = viewports.find(',', start);
    const std::string name = viewports.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    if (name.empty()) throw std::invalid_argument("--viewports " + viewports + ": an empty back-end name");
    o.viewports.push_back(name);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (o.viewports.size() > 8) throw std::invalid_argument("--viewports: at most 8 viewports side by side");
  if (o.width / o.viewports.size() < 16)
    throw std::invalid_argument("--size " + size + ": too narrow for " + std::to_string(o.viewports.size()) +
                                " viewports (16 pixels each at least)");
  if (o.cluster.empty() && (!o.nodes.empty() || !o.tokenFile.empty()))
    throw std::invalid_argument("--nodes and --token-file go with --cluster CONFIG");
  if (o.exitAfter && o.script.empty()) throw std::invalid_argument("--exit-after needs --script FILE");
  for (const auto& p : params) {
    auto [name, value] = med::Parameters::parse(p);
    if (o.parameters.has(name)) throw std::invalid_argument("--param " + p + ": '" + name + "' is given twice");
    o.parameters.set(name, value);
  }
  // A setting is given once: by --param or by its own option, not both.
  for (const auto& [option, name] : {std::pair{depthOption, "maxDepth"}, std::pair{threadsOption, "threads"}})
    if (*option && o.parameters.has(name))
      throw std::invalid_argument(option->get_name() + " and --param " + name + " both set '" + name +
                                  "': give it once");
  if (*depthOption || !o.parameters.has("maxDepth")) o.parameters.set("maxDepth", maxDepth);
  if (*threadsOption || !o.parameters.has("threads")) o.parameters.set("threads", threads);
  usePreviewDefaultsUnlessSet(o.parameters);
  return true;
}

}  // namespace tsr::app
