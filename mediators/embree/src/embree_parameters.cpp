#include "embree_parameters.hpp"

#include <algorithm>

#include "tsr/embree/photon_sequence.hpp"
#include "tsr/embree/render_settings.hpp"
#include "tsr/temporal/truncation.hpp"

namespace tsr::med::embree_mediator {

namespace {

constexpr double kUnbounded = std::numeric_limits<double>::infinity();
constexpr std::int64_t kMaxSpp = 1 << 20;

// embree::describeSettings as parameter specs, with RenderSettings' defaults.
struct TracerSpecs {
  std::vector<ParameterSpec> specs;
  const embree::RenderSettings defaults;
  template <class T>
  void integer(const char* name, T embree::RenderSettings::*field, std::int64_t min, std::int64_t max,
               const char* help) {
    specs.push_back(integerParameter(name, static_cast<std::int64_t>(defaults.*field), min, max, help));
  }
  void flag(const char* name, bool embree::RenderSettings::*field, const char* help) {
    specs.push_back(flagParameter(name, defaults.*field, help));
  }
  template <class E>
  void choice(const char* name, E embree::RenderSettings::*field, std::initializer_list<embree::Named<E>> values,
              const char* help) {
    std::vector<std::string> names;
    std::string fallback;
    for (const auto& v : values) {
      names.emplace_back(v.name);
      if (v.value == defaults.*field) fallback = v.name;
    }
    specs.push_back(choiceParameter(name, fallback, std::move(names), help));
  }
};

// And back: the parameters into the fields describeSettings names.
struct TracerSettingsReader {
  const ParameterTable& table;
  const Parameters& parameters;
  embree::RenderSettings& settings;
  template <class T>
  void integer(const char* name, T embree::RenderSettings::*field, std::int64_t, std::int64_t, const char*) {
    settings.*field = static_cast<T>(table.integer(parameters, name));
  }
  void flag(const char* name, bool embree::RenderSettings::*field, const char*) {
    settings.*field = table.flag(parameters, name);
  }
  template <class E>
  void choice(const char* name, E embree::RenderSettings::*field, std::initializer_list<embree::Named<E>> values,
              const char*) {
    const std::string chosen = table.choice(parameters, name);
    for (const auto& v : values)
      if (chosen == v.name) settings.*field = v.value;
  }
};

// Sampling, the filters (Schwenk, chapters 3 and 4) and the temporal
// methods, in the order --list-params prints them (the tracer's own,
// embree::describeSettings, come right after spp).
std::vector<ParameterSpec> specs() {
  const embree::PhotonSettings photons;
  const temporal::TruncationRule pca;
  TracerSpecs tracer;  // the path tracer's own settings, said there once
  embree::describeSettings(tracer);
  std::vector<ParameterSpec> all = {
      // Figure 5.6's chain: the path tracer converges, and a Whitted-style
      // image (one sample: sharp reflections, refractions and hard shadows,
      // no indirect light, no filter) bridges the moment the camera rests.
      choiceParameter("mode", "path", {"path", "whitted"}, "renderer: progressive path tracer, or one Whitted sample"),
      integerParameter("spp", 16, 1, kMaxSpp, "samples per pixel the progressive image converges to"),
      flagParameter("seedPerFrame", false,
                    "each animation frame draws its own random numbers (seed + frame): noise moves with the "
                    "picture instead of sticking to the screen"),
      flagParameter("directOnly", false, "direct light only (maxDepth 1)"),
      choiceParameter("filter", "none", {"none", "pixel", "atrous", "radiance", "hybrid", "denoise"}, "preview filter"),
      choiceParameter("pathClass", "indirect", {"indirect", "caustic", "all"}, "paths the filter smooths"),
      choiceParameter("filterKernel", "separable", {"bilateral", "separable"}, "pixel filter kernel"),
      // A 10 % relative standard deviation: low enough that 8 spp previews
      // reach well over 64 equivalent spp, high enough that the blend lets go
      // of the filtered image by ~1000 spp on a diffuse box (tests/bench/quality).
      realParameter("threshold", 0.01, 0, 1e6, "perceived variance kept under"),
      positiveParameter("sigmaS", 8.0, 64, "spatial std. dev., pixels"),
      positiveParameter("sigmaC", 0.02, 1e6, "range colour std. dev."),
      positiveParameter("sigmaD", 0.1, 1e6, "range depth std. dev., fraction of the frame's depth extent"),
      // Defaults chosen on the quality suite (docs/filtering.md): the
      // separable kernel (3.14) costs a seventh of the brute-force one for
      // the same seen error; adaptive widths (3.15-3.17) shrink the kernel
      // as samples grow, which keeps glossy reflections and makes the filter
      // fade by 1024 spp; spike removal (3.18) keeps fireflies out of the
      // preview, its interval widening with the samples (pixel_filter.hpp).
      flagParameter("adaptiveWidth", true, "kernel narrows as samples grow (3.15-3.17)"),
      flagParameter("spikeRemoval", true, "fireflies kept out of the preview (3.18)"),
      flagParameter("antialiasRecovery", false, "mixed pixels recovered by coverage (separable kernel only)"),
      // Weber's law fails in the dark (de Vries-Rose): below a background of
      // about 0.1 noise is judged in absolute terms.
      positiveParameter("minBackground", 0.1, 1e6, "background below which noise is judged absolutely"),
      positiveParameter("warmupRadius", 8.0, 1e6, "radiance filter: radius of the first frames, pixels"),
      integerParameter("warmupFrames", 4, 1, kMaxSpp, "radiance filter: frames at the warm-up radius"),
      positiveParameter("maxRadius", 12.0, 64, "radiance filter: largest gather radius, pixels"),
      flagParameter("ambientOcclusion", true, "radiance filter: occlusion-aware weights"),
      flagParameter("bilateral", false, "radiance filter: bilateral weights"),
      realParameter("radianceBlend", 0.0, 0, 1e6, "radiance filter: blend towards the unfiltered image"),
      // The whole-image denoiser (filter=denoise): its method, the regression's
      // window and patches (measured on the suite, docs/filtering.md), then
      // the a-trous levels and edge stops (SVGF's, the luminance one tighter:
      // one frame's variance, not a history's; measured on builtin:cornell).
      choiceParameter("denoiseMethod", "regression", {"regression", "atrous"},
                      "denoiser: first-order regression (NFOR) or the cheaper a-trous wavelet"),
      integerParameter("denoiseRadius", 7, 1, 32, "denoiser (regression): window radius, px"),
      integerParameter("denoisePatch", 3, 0, 8, "denoiser (regression): non-local-means patch radius, px"),
      integerParameter("denoiseLevels", 5, 1, 10, "denoiser: a-trous levels (footprint 4 * (2^levels - 1) + 1 px)"),
      positiveParameter("denoiseSigmaL", 2.0, 1e6, "denoiser: luminance difference kept apart, in standard errors"),
      realParameter("denoiseSigmaN", 64.0, 0, 1e6, "denoiser: exponent on the cosine between normals"),
      positiveParameter("denoiseSigmaZ", 1.0, 1e6, "denoiser: depth difference kept apart, in depth steps per pixel"),
      // Temporal reprojection (FrameBuffer::reproject): the interactive
      // programs turn it on; the limit was measured on an orbit (docs/viewer.md).
      flagParameter("history", false,
                    "a moving camera or moving objects keep the samples of the surfaces still in view, reprojected, "
                    "instead of restarting"),
      integerParameter("historyLimit", 16, 1, 1 << 16,
                       "history: samples a pixel carries over a move at most (light that changed fades within them)"),
      choiceParameter("temporal", "", {"", "photons", "objectPca"}, "temporal method of an animation"),
      integerParameter("photonsPerFrame", 0, 0, 1 << 30, "photons traced per frame (0: automatic)"),
      integerParameter("photonFrames", 9, 1, 255, "odd window of frames photons are gathered from"),
      realParameter("photonAccuracy", photons.accuracy, -kUnbounded, kUnbounded, "sigma_% of eq. 4"),
      realParameter("photonMaxError", photons.maxError, -kUnbounded, kUnbounded, "E_max of eq. 3"),
      realParameter("photonEmissionStep", photons.emissionStep, -kUnbounded, kUnbounded,
                    "relative change of a source's power that ends a window"),
      integerParameter("pcaWindow", 64, 2, 100000, "frames per PCA window"),
      integerParameter("pcaOverlap", 16, 0, INT64_MAX,
                       "frames shared by neighbouring windows (unset: window/4, at most 16)"),
      integerParameter("pcaModes", 0, 0, 1 << 20, "fixed number of PCA modes (0: by the truncation rule)"),
      realParameter("pcaEpsilon", pca.epsilon, -kUnbounded, kUnbounded, "unexplained fraction allowed"),
      realParameter("pcaEpsilonChange", pca.epsilonChange, -kUnbounded, kUnbounded,
                    "improvement by one more mode below which it is noise"),
      flagParameter("pcaPlainRule", false, "the paper's truncation rule, without the noise measure"),
  };
  // The tracer's own right after the sample count.
  const auto spp = std::find_if(all.begin(), all.end(), [](const ParameterSpec& p) { return p.name == "spp"; });
  all.insert(spp + 1, tracer.specs.begin(), tracer.specs.end());
  return all;
}

}  // namespace

embree::RenderSettings renderSettingsFrom(const Parameters& p, std::int64_t frame) {
  embree::RenderSettings s;
  const ParameterTable& t = embreeParameters();
  TracerSettingsReader reader{t, p, s};
  embree::describeSettings(reader);
  if (t.flag(p, "seedPerFrame") && frame >= 0) s.seed += static_cast<std::uint64_t>(frame);
  if (t.flag(p, "directOnly")) s.maxDepth = 1;
  s.historyLimit = t.flag(p, "history") ? static_cast<std::uint32_t>(t.integer(p, "historyLimit")) : 0;
  return s;
}

const BackendCapabilities& embreeCapabilities() {
  static const BackendCapabilities capabilities{ParameterTable("embree", specs()), true, true, true};
  return capabilities;
}

}  // namespace tsr::med::embree_mediator
