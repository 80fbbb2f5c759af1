#include "render_options.hpp"

#include "command_line.hpp"
#include "import_limit_options.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <stdexcept>

#include <CLI/CLI.hpp>

namespace tsr::app {

namespace {
constexpr std::uint64_t kMaxImagePixels = std::uint64_t{1} << 26;
}  // namespace

void parseSize(const std::string& text, std::uint32_t& width, std::uint32_t& height) {
  auto x = text.find('x');
  auto number = [&](std::string_view s) {
    std::uint32_t v = 0;
    auto [end, err] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (err != std::errc() || end != s.data() + s.size() || v == 0 || v > 32768)
      throw std::invalid_argument("--size " + text + ": expected WxH with each side 1..32768");
    return v;
  };
  if (x == std::string::npos) throw std::invalid_argument("--size " + text + ": expected WxH, e.g. 512x512");
  width = number(std::string_view(text).substr(0, x));
  height = number(std::string_view(text).substr(x + 1));
  // Colour, depth and outputs take 20+ bytes a pixel: refuse what no machine
  // here could hold before a back-end tries to allocate it.
  if (std::uint64_t{width} * height > kMaxImagePixels)
    throw std::invalid_argument("--size " + text + ": more than " + std::to_string(kMaxImagePixels) +
                                " pixels (8192x8192)");
}

sg::Vec3 parsePoint(const std::string& option, const std::string& text) {
  sg::Vec3 p(0.0f);
  std::size_t start = 0;
  for (int i = 0; i < 3; ++i) {
    const std::size_t comma = text.find(',', start);
    if ((i < 2) != (comma != std::string::npos))
      throw std::invalid_argument(option + " " + text + ": expected X,Y,Z (three numbers separated by commas)");
    const std::string part = text.substr(start, i < 2 ? comma - start : std::string::npos);
    const char* begin = part.c_str();
    char* end = nullptr;
    p[i] = std::strtof(begin, &end);
    if (part.empty() || end != begin + part.size() || std::isspace(static_cast<unsigned char>(part.front())))
      throw std::invalid_argument(option + " " + text + ": '" + part + "' is not a number");
    start = comma + 1;
  }
  return p;
}

std::string aovPath(const std::string& output, const std::string& aov) {
  auto dot = output.find_last_of('.');
  auto slash = output.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return output + "." + aov;
  return output.substr(0, dot) + "." + aov + output.substr(dot);
}

std::string importLimitOption(const sg::ImportLimitError& e) {
  return e.limit() == sg::ImportLimitError::Limit::FileBytes ? "--max-file-mb" : "--max-elements";
}

bool parseRenderOptions(int argc, char** argv, RenderOptions& o) {
  CLI::App app{"Render a scene with one of Tessera's back-ends"};
  std::string size = "512x512";
  std::int64_t spp = 16, maxDepth = 8, seed = 0, threads = 0;
  std::vector<std::string> params;
  app.add_option("scene", o.scene, "glTF file (.gltf/.glb) or builtin:NAME")->required();
  auto* backendOption =
      app.add_option("--backend", o.backend, "embree, vulkan or coverage (with --cluster: the config's)");
  app.add_option("--size", size, "image size WxH");
  auto* sppOption = app.add_option("--spp", spp, "samples per pixel")->check(CLI::Range(1, 1 << 20));
  auto* depthOption = app.add_option("--max-depth", maxDepth, "maximum path depth")->check(CLI::Range(0, 1024));
  auto* seedOption = app.add_option("--seed", seed, "random seed")->check(CLI::NonNegativeNumber);
  auto* threadsOption = app.add_option("--threads", threads, "render threads (0: all)")->check(CLI::Range(0, 4096));
  app.add_option("--output", o.output, "image file; the format follows the extension")->check(FileName());
  app.add_option("--aov", o.aovs, "extra outputs to write next to --output (albedo, normal, depth, direct, ...)");
  app.add_option("--stats-json", o.statsJson, "write render statistics as JSON")->check(FileName());
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
  filterOptions.emplace_back(filterGroup->add_option("--filter", filter, "none, pixel, atrous, radiance or hybrid")
                                 ->check(CLI::IsMember({"none", "pixel", "atrous", "radiance", "hybrid"})),
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
                 "layered window, composited by depth: BACKEND[:NODE],... bottom first, or a .json file (see the "
                 "README); with --cluster the layer of the config's back-end renders on the nodes");
  if (!parseCommandLine(app, argc, argv)) return false;
  parseSize(size, o.width, o.height);
  if (*fromOption) o.view.look.from = parsePoint("--look-from", lookFrom);
  if (*atOption) o.view.look.at = parsePoint("--look-at", lookAt);
  if (*fovOption) o.view.look.fovDegrees = static_cast<float>(fov);
  sg::validate(o.view.look);
  o.view.defaultLight = !noDefaultLight;
  if (*exposureOption && !(std::isfinite(exposure) && std::abs(exposure) <= 64))
    throw std::invalid_argument("--exposure " + std::to_string(exposure) + ": expected stops between -64 and 64");
  o.display.exposureEv = static_cast<float>(exposure);
  o.display.curve = med::parseToneCurve(tonemap);
  o.backendGiven = backendOption->count() > 0;
  checkTemporalOptions(o.temporal, static_cast<int>(spp));
  if (!o.statsJson.empty() && !o.sequence.cluster.empty())
    throw std::invalid_argument("--stats-json with --cluster: the nodes report no ray counts or conversion times to "
                                "add up (measure a node with a local render)");
  if (o.temporal.active() && !o.sequence.framesGiven)
    throw std::invalid_argument("--temporal " + o.temporal.method + " needs --frames N");
  limits.apply(o.import);
  for (const auto& p : params) {
    auto [name, value] = med::Parameters::parse(p);
    o.parameters.set(name, value);
    o.explicitParameters.insert(name);
  }
  auto flag = [&](CLI::Option* option, const std::string& name, std::int64_t value) {
    if (*option) o.explicitParameters.insert(name);
    if (*option || !o.parameters.has(name)) o.parameters.set(name, value);
  };
  flag(sppOption, "spp", spp);
  flag(depthOption, "maxDepth", maxDepth);
  flag(seedOption, "seed", seed);
  flag(threadsOption, "threads", threads);
  for (const auto& [option, name] : filterOptions) {
    if (!*option) continue;
    o.explicitParameters.insert(name);
    auto [unused, value] = med::Parameters::parse(name + "=" + option->as<std::string>());
    o.parameters.set(name, value);
  }
  o.temporal.applyTo(o.parameters);
  return true;
}

}  // namespace tsr::app
