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

namespace {

// What parseRenderOptions' options hold until the command line is parsed,
// and the options whose presence counts.
struct RenderOptionValues {
  std::string size = "512x512";
  std::int64_t spp = 16, maxDepth = 0, seed = 0, threads = 0;  // depth, seed, threads: the table's defaults
  bool seedPerFrame = false;
  std::vector<std::string> params;
  CLI::Option *backendOption = nullptr, *sppOption = nullptr, *depthOption = nullptr, *seedOption = nullptr,
              *seedPerFrameOption = nullptr, *threadsOption = nullptr;
  ImportLimitOptions limits;
  // Noise filtering: each option with the viewport parameter it sets.
  std::vector<std::pair<CLI::Option*, std::string>> filterOptions;
  std::string filter, pathClass, filterKernel;
  double threshold = 0, sigmaS = 0, sigmaC = 0, sigmaD = 0;
  // The view.
  std::string lookFrom, lookAt, tonemap = "none", focusOn, shutter;
  double fov = 0, exposure = 0, aperture = 0, focusDistance = 0, fNumber = 0;
  bool noDefaultLight = false;
  CLI::Option *fromOption = nullptr, *atOption = nullptr, *fovOption = nullptr, *apertureOption = nullptr,
              *fNumberOption = nullptr, *focusOption = nullptr, *focusOnOption = nullptr, *shutterOption = nullptr,
              *exposureOption = nullptr;
};

// The scene, the back-end and its common settings, the outputs, --param and the import limits.
void addRenderOptions(CLI::App& app, int argc, char** argv, RenderJob& o, std::string& listParams,
                      RenderOptionValues& v) {
  auto* sceneOption = app.add_option("scene", o.scene, sceneArgumentHelp() + " (required unless --list-params)");
  // Required, so options taking several values (--aov, --param) leave it be.
  const bool listing = std::any_of(argv + 1, argv + argc,
                                   [](const char* a) { return std::string_view(a).starts_with("--list-params"); });
  if (!listing) sceneOption->required();
  app.add_option("--list-params", listParams,
                 "print the parameters a back-end takes (for --param NAME=VALUE): name, type and range, default, "
                 "meaning; then stop");
  v.backendOption = app.add_option("--backend", o.backend, backendChoices() + " (with --cluster: the config's)")
                        ->capture_default_str();
  app.add_option("--size", v.size, "image size WxH")->capture_default_str();
  v.sppOption =
      app.add_option("--spp", v.spp, "samples per pixel")->check(CLI::Range(1, 1 << 20))->capture_default_str();
  v.depthOption = addParameterOption(app, "--max-depth", "embree", "maxDepth", v.maxDepth);
  v.seedOption = addParameterOption(app, "--seed", "embree", "seed", v.seed);
  v.seedPerFrameOption = app.add_flag(
      "--seed-per-frame", v.seedPerFrame,
      "with --frames, each frame draws its own random numbers (seed + frame): the noise moves instead of sticking to "
      "the screen as objects move through it (path tracer; default: one seed, as Cycles does)");
  v.threadsOption = addParameterOption(app, "--threads", "embree", "threads", v.threads);
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
  app.add_option("--param", v.params, "back-end parameter name=value (repeatable)");
  app.add_flag("--quiet", o.quiet, "no progress bar");
  v.limits.add(app, o.import);
}

// Noise filtering of the path tracer: each option sets the viewport
// parameter named after it (see the embree back-end's README).
void addFilterOptions(CLI::App& app, RenderOptionValues& v) {
  auto* filterGroup = app.add_option_group("Filtering (embree)", "low-noise previews: Schwenk, chapters 3 and 4");
  v.filterOptions.emplace_back(
      filterGroup->add_option("--filter", v.filter, "none, pixel, atrous, radiance, hybrid or denoise")
          ->check(CLI::IsMember({"none", "pixel", "atrous", "radiance", "hybrid", "denoise"})),
      "filter");
  v.filterOptions.emplace_back(
      filterGroup->add_option("--threshold", v.threshold, "perceived variance kept under (default 0.01)")
          ->check(FiniteNonNegative()),
      "threshold");
  v.filterOptions.emplace_back(
      filterGroup->add_option("--sigma-s", v.sigmaS, "spatial std. dev., pixels (default 8)")->check(FinitePositive()),
      "sigmaS");
  v.filterOptions.emplace_back(
      filterGroup->add_option("--sigma-c", v.sigmaC, "range colour std. dev. (default 0.02)")->check(FinitePositive()),
      "sigmaC");
  v.filterOptions.emplace_back(
      filterGroup
          ->add_option("--sigma-d", v.sigmaD,
                       "range depth std. dev., fraction of the frame's depth extent (default 0.1)")
          ->check(FinitePositive()),
      "sigmaD");
  v.filterOptions.emplace_back(
      filterGroup->add_option("--path-class", v.pathClass, "paths filtered: indirect, caustic or all")
          ->check(CLI::IsMember({"indirect", "caustic", "all"})),
      "pathClass");
  v.filterOptions.emplace_back(
      filterGroup
          ->add_option("--filter-kernel", v.filterKernel, "separable (default) or bilateral (with --filter pixel)")
          ->check(CLI::IsMember({"bilateral", "separable"})),
      "filterKernel");
}

// The camera, the lens and shutter, default lights and the picture's tone.
void addViewOptions(CLI::App& app, RenderJob& o, RenderOptionValues& v) {
  auto* viewGroup = app.add_option_group("View", "camera, default lights and the picture's tone");
  viewGroup->add_option("--camera", o.view.camera,
                        "the scene camera to look through: its name or index (default: the first)");
  v.fromOption =
      viewGroup->add_option("--look-from", v.lookFrom, "eye position X,Y,Z (world units); overrides the camera");
  v.atOption = viewGroup->add_option("--look-at", v.lookAt,
                                     "point looked at X,Y,Z (default with --look-from: the bounds' centre)");
  v.fovOption = viewGroup->add_option("--fov", v.fov, "vertical field of view in degrees, 0 < fov < 180");
  v.apertureOption = viewGroup->add_option(
      "--aperture", v.aperture, "thin lens radius in scene units: depth of field (embree; 0: a pinhole, the default)");
  v.fNumberOption = viewGroup->add_option(
      "--f-number", v.fNumber,
      "the lens as an f-number instead of --aperture: radius = focal length / (2 N), the focal length a full-frame "
      "camera has at this field of view, in metres converted to the scene's unit (glTF: metres; builtin:cornell: "
      "millimetres)");
  v.fNumberOption->excludes(v.apertureOption);
  v.focusOption =
      viewGroup->add_option("--focus-distance", v.focusDistance, "distance in focus along the view, scene units");
  v.focusOnOption = viewGroup->add_option("--focus-on", v.focusOn,
                                          "pixel X,Y: focus at the depth it sees (instead of --focus-distance)");
  v.focusOnOption->excludes(v.focusOption);
  v.shutterOption = viewGroup->add_option(
      "--shutter", v.shutter,
      "OPEN,CLOSE as fractions of the frame interval (1 / --fps): what the animation moves is blurred between "
      "(embree; e.g. 0,0.5; default 0,0: an instant). Without --frames, the first frame's motion");
  viewGroup->add_flag("--no-default-light", v.noDefaultLight,
                      "a scene without lights stays unlit (default: a grey dome and a camera light)");
  v.exposureOption = viewGroup->add_option("--exposure", v.exposure,
                                           "exposure in stops for 8-bit outputs (PNG, JPEG); EXR stays linear");
  viewGroup
      ->add_option("--tonemap", v.tonemap, "tone curve for 8-bit outputs: none or filmic (ACES fitted, Narkowicz 2015)")
      ->check(CLI::IsMember({"none", "filmic"}));
}

// The view options into the job's look, focus, lights and display, checked.
void applyViewOptions(const RenderOptionValues& v, RenderJob& o) {
  if (*v.fromOption) o.view.look.from = parsePoint("--look-from", v.lookFrom);
  if (*v.atOption) o.view.look.at = parsePoint("--look-at", v.lookAt);
  if (*v.fovOption) o.view.look.fovDegrees = static_cast<float>(v.fov);
  if (*v.apertureOption) o.view.look.apertureRadius = static_cast<float>(v.aperture);
  if (*v.fNumberOption) o.view.look.fNumber = static_cast<float>(v.fNumber);
  if (*v.focusOption) o.view.look.focusDistance = static_cast<float>(v.focusDistance);
  if (*v.shutterOption) o.view.look.shutter = parseShutter(v.shutter);
  if (*v.focusOnOption) {
    const std::string& focusOn = v.focusOn;
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
  o.view.defaultLight = !v.noDefaultLight;
  if (*v.exposureOption && !(std::isfinite(v.exposure) && std::abs(v.exposure) <= 64))
    throw std::invalid_argument("--exposure " + std::to_string(v.exposure) + ": expected stops between -64 and 64");
  o.display.exposureEv = static_cast<float>(v.exposure);
  o.display.curve = med::parseToneCurve(v.tonemap);
}

// --param and the options that set a back-end parameter, into the job's
// parameters. A setting is given once: by --param or by its own option, not
// both (a --param the option overrode would go unchecked and unused).
void applyParameterOptions(const RenderOptionValues& v, RenderJob& o) {
  std::map<std::string, std::string> givenBy;
  auto claim = [&](const std::string& name, const std::string& by) {
    if (auto [it, fresh] = givenBy.emplace(name, by); !fresh)
      throw std::invalid_argument(by + " and " + it->second + " both set '" + name + "': give it once");
    o.explicitParameters.insert(name);
  };
  for (const auto& p : v.params) {
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
  flag(v.sppOption, "spp", v.spp);
  flag(v.depthOption, "maxDepth", v.maxDepth);
  flag(v.seedOption, "seed", v.seed);
  if (*v.seedPerFrameOption && v.seedPerFrame) {
    claim("seedPerFrame", "--seed-per-frame");
    o.parameters.set("seedPerFrame", true);
  }
  flag(v.threadsOption, "threads", v.threads);
  for (const auto& [option, name] : v.filterOptions) {
    if (!*option) continue;
    claim(name, option->get_name());
    auto [unused, value] = med::Parameters::parse(name + "=" + option->as<std::string>());
    o.parameters.set(name, value);
  }
}

}  // namespace

// The options by concern (render, filtering, view, temporal, sequence,
// layers), then what they hold applied to the job in the same order as
// they were checked before.
bool parseRenderOptions(int argc, char** argv, RenderJob& o, std::string& listParams) {
  CLI::App app{"Render a scene with one of Tessera's back-ends"};
  RenderOptionValues v;
  addRenderOptions(app, argc, argv, o, listParams, v);
  addFilterOptions(app, v);
  addViewOptions(app, o, v);
  addTemporalOptions(app, o.temporal);
  addSequenceOptions(app, o.sequence);
  app.add_option("--layers", o.layers,
                 "layered window, composited by depth: BACKEND[:NODE],... bottom first, or a .json file (see "
                 "docs/rendering.md); with --cluster the layer of the config's back-end renders on the nodes");
  if (!parseCommandLine(app, argc, argv)) return false;
  if (!listParams.empty()) return true;
  parseSize(v.size, o.width, o.height);
  applyViewOptions(v, o);
  o.backendGiven = v.backendOption->count() > 0;
  v.limits.apply(o.import);
  applyParameterOptions(v, o);
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
