#include "filter_settings.hpp"

#include <cmath>
#include <vector>

namespace tsr::med::embree_mediator {

namespace {

// A 10 % relative standard deviation: low enough that 8 spp previews reach
// well over 64 equivalent spp, high enough that the blend lets go of the
// filtered image by ~1000 spp on a diffuse box (tests/bench/quality).
constexpr double kDefaultThreshold = 0.01;

template <class Enum>
Enum choose(const Parameters& p, const std::string& name, const std::string& fallback,
            const std::vector<std::pair<std::string, Enum>>& choices) {
  const std::string value = p.getString(name, fallback);
  std::string known;
  for (const auto& [text, e] : choices) {
    if (text == value) return e;
    known += (known.empty() ? "" : ", ") + text;
  }
  throw ParameterError("parameter " + name + ": '" + value + "' is not one of " + known);
}

float positive(const Parameters& p, const std::string& name, double fallback, bool zeroAllowed = false) {
  const double v = p.getReal(name, fallback);
  if (!std::isfinite(v) || v < 0.0 || (!zeroAllowed && v == 0.0) || v > 1e6)
    throw ParameterError("parameter " + name + ": " + std::to_string(v) + " must be " +
                         (zeroAllowed ? "at least 0" : "above 0") + " and at most 1e6");
  return static_cast<float>(v);
}

}  // namespace

FilterSettings FilterSettings::from(const Parameters& p) {
  FilterSettings s;
  s.mode = choose<FilterMode>(p, "filter", "none",
                              {{"none", FilterMode::None},
                               {"pixel", FilterMode::Pixel},
                               {"atrous", FilterMode::Atrous},
                               {"radiance", FilterMode::Radiance},
                               {"hybrid", FilterMode::Hybrid}});
  s.pathClass =
      choose<PathClass>(p, "pathClass", "indirect",
                        {{"indirect", PathClass::Indirect}, {"caustic", PathClass::Caustic}, {"all", PathClass::All}});
  s.pixel.kernel = choose<embree::FilterKernel>(
      p, "filterKernel", "separable",
      {{"bilateral", embree::FilterKernel::Bilateral}, {"separable", embree::FilterKernel::Separable}});
  if (s.mode == FilterMode::Atrous) s.pixel.kernel = embree::FilterKernel::Atrous;
  s.pixel.threshold = positive(p, "threshold", kDefaultThreshold, true);
  s.pixel.sigmaS = positive(p, "sigmaS", 8.0);
  if (s.pixel.sigmaS > 64.0f) throw ParameterError("parameter sigmaS: at most 64 pixels");
  s.pixel.sigmaC = positive(p, "sigmaC", 0.02);
  s.sigmaDRelative = positive(p, "sigmaD", 0.1);
  // Defaults chosen on the quality suite (docs/filtering.md): the separable
  // kernel (3.14) costs a seventh of the brute-force one for the same seen
  // error; adaptive widths (3.15-3.17) shrink the kernel as samples grow,
  // which keeps glossy reflections and makes the filter fade by 1024 spp;
  // spike removal (3.18) keeps fireflies out of the preview; its interval
  // widens with the samples, or it kept the 1024-spp image up to 3x off
  // the unfiltered one (pixel_filter.hpp).
  s.pixel.adaptiveWidth = p.getBool("adaptiveWidth", true);
  s.pixel.spikeRemoval = p.getBool("spikeRemoval", true);
  s.pixel.antialiasRecovery = p.getBool("antialiasRecovery", false);
  if (s.pixel.antialiasRecovery && s.pixel.kernel != embree::FilterKernel::Separable)
    throw ParameterError("parameter antialiasRecovery: works with filterKernel=separable only");
  // Weber's law fails in the dark (de Vries-Rose): below a background of
  // about 0.1, noise is judged in absolute terms, so dark pixels are not
  // held to a far stricter threshold than the rest, nor kept filtered long
  // after the rest of the image let go.
  s.pixel.minBackground = positive(p, "minBackground", 0.1);
  s.pixel.threads = static_cast<int>(p.getInt("threads", 0, 0, 4096));
  s.radiance.threshold = positive(p, "threshold", kDefaultThreshold, true);
  s.radiance.warmupRadius = positive(p, "warmupRadius", 8.0);
  s.radiance.warmupFrames = static_cast<std::uint32_t>(p.getInt("warmupFrames", 4, 1, 1 << 20));
  s.radiance.maxRadius = positive(p, "maxRadius", 12.0);
  if (s.radiance.maxRadius > 64.0f) throw ParameterError("parameter maxRadius: at most 64 pixels");
  s.radiance.ambientOcclusion = p.getBool("ambientOcclusion", true);
  s.radiance.bilateral = p.getBool("bilateral", false);
  s.radiance.blend = positive(p, "radianceBlend", 0.0, true);
  s.radiance.hybrid = s.mode == FilterMode::Hybrid;
  try {
    s.radiance.validate();
  } catch (const std::exception& e) {
    throw ParameterError(std::string("radiance filter parameters: ") + e.what());
  }
  return s;
}

}  // namespace tsr::med::embree_mediator
