#include "sequence/temporal_options.hpp"

#include <stdexcept>

#include "command_line.hpp"

namespace tsr::app {

void addTemporalOptions(CLI::App& app, TemporalOptions& o) {
  auto* g =
      app.add_option_group("Temporal (with --frames)", "flicker-free animations: indirect light denoised over time");
  g->add_option("--temporal", o.method,
                "pca: project the indirect light onto its temporal PCA basis (Meyer & Anderson); photons: "
                "spatio-temporal photon density estimation (--backend embree); reproject: each frame adds --spp "
                "samples to the samples of the frame before, reprojected to its view where the same surfaces show "
                "(--backend embree's history, as the interactive programs use it). With pca --spp is the indirect "
                "sample count, with photons the direct one")
      ->check(CLI::IsMember({"pca", "photons", "reproject"}));
  g->add_option("--temporal-space", o.space,
                "where pca projects: image (the frames' indirect light), object (irradiance on surface elements "
                "fixed to the meshes, estimated by --photons-per-frame photons per frame; --spp is then the direct "
                "sample count) or auto (default): object when the camera moves, so visibility changes are not "
                "taken for lighting changes")
      ->check(CLI::IsMember({"auto", "image", "object"}));
  g->add_option("--direct-spp", o.directSpp,
                "direct-light samples per pixel and frame (default: --spp; direct light has the lower variance, "
                "so its noise stays under the denoised indirect's)")
      ->check(CLI::Range(1, 1 << 20));
  g->add_option("--temporal-modes", o.modes, "keep this many PCA modes (default: chosen by --temporal-epsilon)")
      ->check(CLI::Range(1, 1 << 20));
  g->add_option("--temporal-epsilon", o.epsilon, "energy fraction the kept modes may leave unexplained (default 0.005)")
      ->check(FiniteRange(0.0, 1.0));
  g->add_option("--temporal-epsilon-change", o.epsilonChange,
                "stop adding modes when one more explains less than this (default 0.001)")
      ->check(FiniteRange(0.0, 1.0));
  g->add_flag("--temporal-plain-rule", o.plainRule,
              "2.3's truncation rule as published: --temporal-epsilon-change alone decides what is noise (default: "
              "the noise level is measured from the modes, see backends/temporal/README.md)");
  g->add_option("--photons-per-frame", o.photonsPerFrame,
                "photons traced per frame (default: chosen by a pilot pass for 10% error, Weber et al. eq. 3)")
      ->check(CLI::Range(1, 1 << 30));
  g->add_option("--photon-frames", o.photonFrames,
                "frames whose photons reconstruct one frame, centred on it; odd (default 9)")
      ->check(CLI::Range(1, 255));
  g->add_flag("--temporal-global", o.global, "one truncation for the whole frame, not a smoothed per-pixel map");
  g->add_option("--temporal-map-sigma", o.mapSigma,
                "Gaussian smoothing of the per-pixel truncation map, pixels (default 2)")
      ->check(FiniteRange(0.0, 64.0));
  g->add_option("--temporal-window", o.window,
                "frames denoised together; longer sequences run in overlapping windows (default 64)")
      ->check(CLI::Range(2, 100000));
  g->add_option("--temporal-overlap", o.overlap,
                "frames two windows share, cross-faded (default: a quarter of the window, at most 16)")
      ->check(CLI::Range(0, 100000));
  g->add_option("--temporal-high-spp", o.highSpp,
                "image-space pca: pixels whose truncation map keeps more than --temporal-m-min modes (light the "
                "basis holds poorly) are rendered again with this many indirect samples and blended in by "
                "alpha = (m - m_min) / (N - m_min) (Meyer & Anderson 3.2; default 0: off)")
      ->check(CLI::Range(1, 1 << 20));
  g->add_option("--temporal-m-min", o.mMin,
                "the truncation above which --temporal-high-spp re-renders a pixel (default: half the window's "
                "frames)")
      ->check(FiniteRange(1.0, 100000.0));
}

void checkTemporalOptions(const TemporalOptions& o, int spp) {
  if (!o.active()) {
    if (o.directSpp || o.modes) throw std::invalid_argument("--direct-spp and --temporal-modes need --temporal");
    return;
  }
  if (o.method == "photons" && o.photonFrames % 2 == 0)
    throw std::invalid_argument("--photon-frames " + std::to_string(o.photonFrames) +
                                " must be odd: the window is centred on the frame it reconstructs");
  if (o.method == "reproject" && o.modes)
    throw std::invalid_argument("--temporal-modes is pca's truncation: it needs --temporal pca");
  if (o.method == "reproject" && o.directSpp)
    throw std::invalid_argument("--direct-spp with --temporal reproject: the history carries whole samples, so "
                                "--spp is the count of every kind of light");
  if (o.method == "photons" && o.directSpp)
    throw std::invalid_argument("--direct-spp with --temporal photons: photons carry the indirect light, so --spp "
                                "is already the direct-light sample count");
  if (o.method == "pca" && o.space == "object" && o.directSpp)
    throw std::invalid_argument("--direct-spp with object-space pca: photons on surface elements carry the indirect "
                                "light, so --spp is already the direct-light sample count");
  if (o.method != "pca" && o.space != "auto")
    throw std::invalid_argument("--temporal-space is where pca projects: it needs --temporal pca");
  if ((o.highSpp || o.mMin) && !(o.method == "pca" && o.space != "object"))
    throw std::invalid_argument(
        "--temporal-high-spp and --temporal-m-min re-render pixels of image-space pca: they need --temporal pca" +
        std::string(o.method == "pca" ? " in image space (this run projects in object space; --temporal-space "
                                        "image forces image space)"
                                      : ""));
  if (o.mMin && !o.highSpp) throw std::invalid_argument("--temporal-m-min needs --temporal-high-spp");
  if (o.highSpp && (o.global || o.modes))
    throw std::invalid_argument("--temporal-high-spp picks pixels by the per-pixel truncation map, which "
                                "--temporal-global and --temporal-modes replace");
  if (o.highSpp && o.highSpp <= spp)
    throw std::invalid_argument("--temporal-high-spp " + std::to_string(o.highSpp) + " must exceed --spp " +
                                std::to_string(spp));
  if (o.overlapFrames() >= o.window)
    throw std::invalid_argument("--temporal-overlap " + std::to_string(o.overlapFrames()) +
                                " must be smaller than --temporal-window " + std::to_string(o.window));
  if (o.directSpp && o.directSpp < spp)
    throw std::invalid_argument("--direct-spp " + std::to_string(o.directSpp) + " is below --spp " +
                                std::to_string(spp) +
                                ": direct light comes from the same paths as the indirect, so it gets at least --spp");
}

void TemporalOptions::resolveSpace(bool cameraMoves) {
  if (method == "pca" && space == "auto") space = cameraMoves ? "object" : "image";
}

void TemporalOptions::applyTo(med::Parameters& parameters) const {
  if (reprojects()) {
    parameters.set("history", true);
    return;
  }
  if (!inBackend()) return;
  parameters.set("photonsPerFrame", std::int64_t{photonsPerFrame});
  if (method == "photons") {
    parameters.set("temporal", std::string("photons"));
    parameters.set("photonFrames", std::int64_t{photonFrames});
    return;
  }
  parameters.set("temporal", std::string("objectPca"));
  parameters.set("pcaWindow", std::int64_t{window});
  parameters.set("pcaOverlap", std::int64_t{overlapFrames()});
  parameters.set("pcaModes", std::int64_t{modes});
  parameters.set("pcaEpsilon", epsilon);
  parameters.set("pcaEpsilonChange", epsilonChange);
  parameters.set("pcaPlainRule", plainRule);
}

}  // namespace tsr::app
