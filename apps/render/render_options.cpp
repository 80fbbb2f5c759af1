#include "render_options.hpp"

#include "backends.hpp"
#include "command_line.hpp"
#include "import_limit_options.hpp"
#include "option_values.hpp"
#include "parameter_option.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <map>
#include <stdexcept>
#include <string_view>

#include <CLI/CLI.hpp>

namespace tsr::app {

bool parseRenderOptions(int argc, char** argv, RenderJob& o, std::string& listParams) {
  CLI::App app{"Render a scene with one of Tessera's back-ends"};
  std::string size = "512x512";
  std::int64_t spp = 16, maxDepth = 0, seed = 0, threads = 0;
  std::vector<std::string> params;
  auto* sceneOption = app.add_option("scene", o.scene, sceneArgumentHelp() + " (required unless --list-params)");
  // Required, so options taking several values (--aov, --param) leave it be.
  const bool listing = std::any_of(argv + 1, argv + argc,
                                   [](const char* a) { return std::string_view(a).starts_with("--list-params"); });
  if (!listing) sceneOption->required();
  app.add_option("--list-params", listParams,
                 "print the parameters a back-end takes (for --param NAME=VALUE): name, type and range, default, "
                 "meaning; then stop");
  auto* backendOption = app.add_option("--backend", o.backend, backendChoices() + " (with --cluster: the config's)")
                            ->capture_default_str();
  app.add_option("--size", size, "image size WxH")->capture_default_str();
  auto* sppOption =
      app.add_option("--spp", spp, "samples per pixel")->check(CLI::Range(1, 1 << 20))->capture_default_str();
  auto* depthOption = addParameterOption(app, "--max-depth", "embree", "maxDepth", maxDepth);
  auto* seedOption = addParameterOption(app, "--seed", "embree", "seed", seed);
  bool seedPerFrame = false;
  auto* seedPerFrameOption = app.add_flag(
      "--seed-per-frame", seedPerFrame,
      "with --frames, each frame draws its own random numbers (seed + frame): the noise moves instead of sticking to "
      "the screen as objects move through it (path tracer; default: one seed, as Cycles does)");
  auto* threadsOption = addParameterOption(app, "--threads", "embree", "threads", threads);
  app.add_option("--output", o.output, "image file; the format follows the extension")
      ->check(FileName())
      ->capture_default_str();
  app.add_option("--aov", o.aovs,
                 "extra outputs to write next to --output (albedo, normal, depth, direct, ...; with --cluster, "
                 "workload: each tile in its node's colour, darker the quicker it rendered)");
  app.add_option("--stats-json", o.statsJson,
                 "write render statistics as JSON (with --cluster: per frame and node, tiles, pixels, samples, "
                 "milliseconds and the balance)")
      ->check(FileName());
  app.add_option("--param", params, "back-end parameter name=value (repeatable)");
  app.add_flag("--quiet", o.quiet, "no progress bar");
  ImportLimitOptions limits;
  limits.add(app, o.import);
  // Noise filtering of the path tracer: each option sets the viewport
  // parameter named after it (see the embree back-end's README).
  std::vector<std::pair<CLI::Option*, std::string>> filterOptions;
  std::string filter, pathClass, filterKernel;
  double threshold = 0, sigmaS = 0, sigmaC = 0, sigmaD = 0;
  auto* filterGroup = app.add_option_group("Filtering (embree)", "low-noise previews: Schwenk, chapters 3 and 4");
  filterOptions.emplace_back(
      filterGroup->add_option("--filter", filter, "none, pixel, atrous, radiance, hybrid or denoise")
          ->check(CLI::IsMember({"none", "pixel", "atrous", "radiance", "hybrid", "denoise"})),
      "filter");
  filterOptions.emplace_back(
      filterGroup->add_option("--threshold", threshold, "perceived variance kept under (default 0.01)")
          ->check(FiniteNonNegative()),
      "threshold");
  filterOptions.emplace_back(
      filterGroup->add_option("--sigma-s", sigmaS, "spatial std. dev., pixels (default 8)")->check(FinitePositive()),
      "sigmaS");
  filterOptions.emplace_back(
      filterGroup->add_option("--sigma-c", sigmaC, "range colour std. dev. (default 0.02)")->check(FinitePositive()),
      "sigmaC");
  filterOptions.emplace_back(
      filterGroup
          ->add_option("--sigma-d", sigmaD, "range depth std. dev., fraction of the frame's depth extent (default 0.1)")
          ->check(FinitePositive()),
      "sigmaD");
  filterOptions.emplace_back(
      filterGroup->add_option("--path-class", pathClass, "paths filtered: indirect, caustic or all")
          ->check(CLI::IsMember({"indirect", "caustic", "all"})),
      "pathClass");
  filterOptions.emplace_back(
      filterGroup->add_option("--filter-kernel", filterKernel, "separable (default) or bilateral (with --filter pixel)")
          ->check(CLI::IsMember({"bilateral", "separable"})),
      "filterKernel");
  std::string lookFrom, lookAt, tonemap = "none";
  double fov = 0, exposure = 0;
  auto* viewGroup = app.add_option_group("View", "camera, default lights and the picture's tone");
  viewGroup->add_option("--camera", o.view.camera,
                        "the scene camera to look through: its name or index (default: the first)");
  auto* fromOption =
      viewGroup->add_option("--look-from", lookFrom, "eye position X,Y,Z (world units); overrides the camera");
  auto* atOption = viewGroup->add_option("--look-at", lookAt,
                                         "point looked at X,Y,Z (default with --look-from: the bounds' centre)");
  auto* fovOption = viewGroup->add_option("--fov", fov, "vertical field of view in degrees, 0 < fov < 180");
  double aperture = 0, focusDistance = 0;
  auto* apertureOption = viewGroup->add_option(
      "--aperture", aperture, "thin lens radius in scene units: depth of field (embree; 0: a pinhole, the default)");
  double fNumber = 0;
  auto* fNumberOption = viewGroup->add_option(
      "--f-number", fNumber,
      "the lens as an f-number instead of --aperture: radius = focal length / (2 N), the focal length a full-frame "
      "camera has at this field of view, in metres converted to the scene's unit (glTF: metres; builtin:cornell: "
      "millimetres)");
  fNumberOption->excludes(apertureOption);
  auto* focusOption =
      viewGroup->add_option("--focus-distance", focusDistance, "distance in focus along the view, scene units");
  std::string focusOn;
  auto* focusOnOption = viewGroup->add_option("--focus-on", focusOn,
                                              "pixel X,Y: focus at the depth it sees (instead of --focus-distance)");
  focusOnOption->excludes(focusOption);
  std::string shutter;
  auto* shutterOption = viewGroup->add_option(
      "--shutter", shutter,
      "OPEN,CLOSE as fractions of the frame interval (1 / --fps): what the animation moves is blurred between "
      "(embree; e.g. 0,0.5; default 0,0: an instant). Without --frames, the first frame's motion");
  bool noDefaultLight = false;
  viewGroup->add_flag("--no-default-light", noDefaultLight,
                      "a scene without lights stays unlit (default: a grey dome and a camera light)");
  auto* exposureOption = viewGroup->add_option("--exposure", exposure,
                                               "exposure in stops for 8-bit outputs (PNG, JPEG); EXR stays linear");
  viewGroup
      ->add_option("--tonemap", tonemap, "tone curve for 8-bit outputs: none or filmic (ACES fitted, Narkowicz 2015)")
      ->check(CLI::IsMember({"none", "filmic"}));
  addTemporalOptions(app, o.temporal);
  addSequenceOptions(app, o.sequence);
  app.add_option("--layers", o.layers,
                 "layered window, composited by depth: BACKEND[:NODE],... bottom first, or a .json file (see "
                 "docs/rendering.md); with --cluster the layer of the config's back-end renders on the nodes");
  if (!parseCommandLine(app, argc, argv)) return false;
  if (!listParams.empty()) return true;
  parseSize(size, o.width, o.height);
  if (*fromOption) o.view.look.from = parsePoint("--look-from", lookFrom);
  if (*atOption) o.view.look.at = parsePoint("--look-at", lookAt);
  if (*fovOption) o.view.look.fovDegrees = static_cast<float>(fov);
  if (*apertureOption) o.view.look.apertureRadius = static_cast<float>(aperture);
  if (*fNumberOption) o.view.look.fNumber = static_cast<float>(fNumber);
  if (*focusOption) o.view.look.focusDistance = static_cast<float>(focusDistance);
  if (*shutterOption) o.view.look.shutter = parseShutter(shutter);
  if (*focusOnOption) {
    std::uint32_t x = 0, y = 0;
    const char* end = focusOn.data() + focusOn.size();
    const auto [afterX, errX] = std::from_chars(focusOn.data(), end, x);
    const bool comma = errX == std::errc() && afterX != end && *afterX == ',';
    const auto [afterY, errY] = comma ? std::from_chars(afterX + 1, end, y) : std::from_chars_result{end, errX};
    if (!comma || errY != std::errc() || afterY != end || x >= o.width || y >= o.height)
      throw std::invalid_argument("--focus-on " + focusOn + ": expected a pixel X,Y inside the " +
                                  std::to_string(o.width) + "x" + std::to_string(o.height) + " image");
    o.view.focusOn = app::FocusOn{x, y, o.width, o.height};
  }
  sg::validate(o.view.look);
  o.view.defaultLight = !noDefaultLight;
  if (*exposureOption && !(std::isfinite(exposure) && std::abs(exposure) <= 64))
    throw std::invalid_argument("--exposure " + std::to_string(exposure) + ": expected stops between -64 and 64");
  o.display.exposureEv = static_cast<float>(exposure);
  o.display.curve = med::parseToneCurve(tonemap);
  o.backendGiven = backendOption->count() > 0;
  limits.apply(o.import);
  // A setting is given once: by --param or by its own option, not both (a
  // --param the option overrode would go unchecked and unused).
  std::map<std::string, std::string> givenBy;
  auto claim = [&](const std::string& name, const std::string& by) {
    if (auto [it, fresh] = givenBy.emplace(name, by); !fresh)
      throw std::invalid_argument(by + " and " + it->second + " both set '" + name + "': give it once");
    o.explicitParameters.insert(name);
  };
  for (const auto& p : params) {
    auto [name, value] = med::Parameters::parse(p);
    claim(name, "--param " + p);
    o.parameters.set(name, value);
  }
  // Unset, the back-end's own default applies (--list-params shows it).
  auto flag = [&](CLI::Option* option, const std::string& name, std::int64_t value) {
    if (!*option) return;
    claim(name, option->get_name());
    o.parameters.set(name, value);
  };
  flag(sppOption, "spp", spp);
  flag(depthOption, "maxDepth", maxDepth);
  flag(seedOption, "seed", seed);
  if (*seedPerFrameOption && seedPerFrame) {
    claim("seedPerFrame", "--seed-per-frame");
    o.parameters.set("seedPerFrame", true);
  }
  flag(threadsOption, "threads", threads);
  for (const auto& [option, name] : filterOptions) {
    if (!*option) continue;
    claim(name, option->get_name());
    auto [unused, value] = med::Parameters::parse(name + "=" + option->as<std::string>());
    o.parameters.set(name, value);
  }
  o.temporal.applyTo(o.parameters);
  return true;
}

void checkRenderJob(const RenderJob& o, const std::vector<LayerSpec>& layers) {
  const SequenceOptions& sequence = o.sequence;
  checkTemporalOptions(o.temporal, static_cast<int>(samplesPerPixel(o)));
  if (asksWorkload(o) && sequence.cluster.empty())
    throw std::invalid_argument("--aov workload shows which cluster node rendered which tile: it needs --cluster");
  // Through a layered window the nodes render one layer of it (a
  // ClusterViewport): that window's statistics are a local render's.
  if (!o.statsJson.empty() && !sequence.cluster.empty() && (!layers.empty() || o.temporal.inBackend()))
    throw std::invalid_argument(std::string("--stats-json with --cluster and ") +
                                (layers.empty() ? "--temporal " + o.temporal.method : std::string("--layers")) +
                                ": the nodes render one layer of a window here, which keeps no per-node figures "
                                "(leave --layers out, or measure a node with a local render)");
  if (sequence.fpsGiven && !sequence.framesGiven && !o.view.look.shutter)
    throw std::invalid_argument("--fps is the frame rate of an animation: it needs --frames N (or --shutter, "
                                "whose blur then spans 1/fps)");
  if (o.temporal.active() && !sequence.framesGiven)
    throw std::invalid_argument("--temporal " + o.temporal.method + " needs --frames N");
  if (sequence.frames > 1 && o.output.find("####") == std::string::npos)
    throw std::invalid_argument("--frames " + std::to_string(sequence.frames) +
                                " needs #### in --output for the frame number");
  if (o.temporal.highSpp && (!sequence.cluster.empty() || !layers.empty()))
    throw std::invalid_argument("--temporal-high-spp re-renders pixels here, with --backend alone: not with "
                                "--cluster or --layers");
  if (!sequence.cluster.empty() && o.temporal.active() && o.temporal.directSpp > samplesPerPixel(o))
    throw std::invalid_argument("--direct-spp: with --cluster the nodes render direct and indirect light in the same "
                                "paths, at --spp (raise --spp or leave --direct-spp out)");
}

}  // namespace tsr::app
