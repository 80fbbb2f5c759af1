#include "filter_settings.hpp"

#include <cmath>
#include <stdexcept>
#include <vector>

#include "embree_parameters.hpp"

namespace tsr::med::embree_mediator {

namespace {

template <class Enum>
Enum choose(const Parameters& p, std::string_view name, const std::vector<std::pair<std::string, Enum>>& choices) {
  const std::string value = embreeParameters().choice(p, name);
  for (const auto& [text, e] : choices)
    if (text == value) return e;
  throw std::logic_error("filter setting " + std::string(name) + " = " + value + " has no meaning");
}

float real(const Parameters& p, std::string_view name) { return static_cast<float>(embreeParameters().real(p, name)); }

}  // namespace

FilterSettings FilterSettings::from(const Parameters& p) {
  FilterSettings s;
  const ParameterTable& t = embreeParameters();
  s.mode = choose<FilterMode>(p, "filter",
                              {{"none", FilterMode::None},
                               {"pixel", FilterMode::Pixel},
                               {"atrous", FilterMode::Atrous},
                               {"radiance", FilterMode::Radiance},
                               {"hybrid", FilterMode::Hybrid},
                               {"denoise", FilterMode::Denoise}});
  s.pathClass = choose<PathClass>(
      p, "pathClass", {{"indirect", PathClass::Indirect}, {"caustic", PathClass::Caustic}, {"all", PathClass::All}});
  s.pixel.kernel = choose<embree::FilterKernel>(
      p, "filterKernel",
      {{"bilateral", embree::FilterKernel::Bilateral}, {"separable", embree::FilterKernel::Separable}});
  // A Whitted image is one noiseless sample: nothing to filter.
  if (t.choice(p, "mode") == "whitted") s.mode = FilterMode::None;
  if (s.mode == FilterMode::Atrous) s.pixel.kernel = embree::FilterKernel::Atrous;
  s.pixel.threshold = real(p, "threshold");
  s.pixel.sigmaS = real(p, "sigmaS");
  s.pixel.sigmaC = real(p, "sigmaC");
  s.sigmaDRelative = real(p, "sigmaD");
  s.pixel.adaptiveWidth = t.flag(p, "adaptiveWidth");
  s.pixel.spikeRemoval = t.flag(p, "spikeRemoval");
  s.pixel.antialiasRecovery = t.flag(p, "antialiasRecovery");
  if (s.pixel.antialiasRecovery && s.pixel.kernel != embree::FilterKernel::Separable)
    throw ParameterError("parameter antialiasRecovery: works with filterKernel=separable only");
  s.pixel.minBackground = real(p, "minBackground");
  s.pixel.threads = static_cast<int>(t.integer(p, "threads"));
  s.radiance.threshold = real(p, "threshold");
  s.radiance.warmupRadius = real(p, "warmupRadius");
  s.radiance.warmupFrames = static_cast<std::uint32_t>(t.integer(p, "warmupFrames"));
  s.radiance.maxRadius = real(p, "maxRadius");
  s.radiance.ambientOcclusion = t.flag(p, "ambientOcclusion");
  s.radiance.bilateral = t.flag(p, "bilateral");
  s.radiance.blend = real(p, "radianceBlend");
  s.radiance.hybrid = s.mode == FilterMode::Hybrid;
  s.denoise.method = choose<embree::DenoiseMethod>(
      p, "denoiseMethod",
      {{"regression", embree::DenoiseMethod::Regression}, {"atrous", embree::DenoiseMethod::Atrous}});
  s.denoise.radius = static_cast<unsigned>(t.integer(p, "denoiseRadius"));
  s.denoise.patchRadius = static_cast<unsigned>(t.integer(p, "denoisePatch"));
  s.denoise.levels = static_cast<unsigned>(t.integer(p, "denoiseLevels"));
  s.denoise.sigmaLuminance = real(p, "denoiseSigmaL");
  s.denoise.sigmaNormal = real(p, "denoiseSigmaN");
  s.denoise.sigmaDepth = real(p, "denoiseSigmaZ");
  s.denoise.threads = static_cast<int>(t.integer(p, "threads"));
  try {
    s.radiance.validate();
  } catch (const std::exception& e) {
    throw ParameterError(std::string("radiance filter parameters: ") + e.what());
  }
  return s;
}

}  // namespace tsr::med::embree_mediator
