#pragma once
// tessera-render's temporal noise reduction options (with --frames):
//   --temporal pca|photons   denoise the indirect light over the sequence
//   --direct-spp N           samples of direct light per frame
//   --temporal-modes M       fixed PCA truncation (default: automatic, 2.3)
//   --temporal-epsilon E, --temporal-epsilon-change C, --temporal-global,
//   --temporal-map-sigma S, --temporal-window W, --temporal-overlap O
//   --photons-per-frame N, --photon-frames T (photons)
#include <CLI/CLI.hpp>

#include <string>

#include "tsr/med/parameters.hpp"

namespace tsr::app {

struct TemporalOptions {
  std::string method;  // empty: frame by frame
  int directSpp = 0;   // 0: the same as --spp (see --help)
  int modes = 0;       // 0: automatic
  double epsilon = 0.005, epsilonChange = 0.001;
  bool plainRule = false;  // --temporal-plain-rule: no noise measurement
  bool global = false;     // one truncation for the whole frame instead of 3.2's map
  double mapSigma = 2.0;
  int window = 64, overlap = 16;
  int photonsPerFrame = 0;  // 0: from the photon pilot pass
  int photonFrames = 9;     // the photon method's temporal window (odd)
  bool active() const { return !method.empty(); }
  // The viewport parameters that select the method in the back-end
  // (photons: the path tracer's photon viewport); none for pca, which
  // works on the rendered frames.
  void applyTo(med::Parameters& parameters) const;
};

// Declares the options on `app` (so --help lists them), in their own group.
void addTemporalOptions(CLI::App& app, TemporalOptions& options);

// Checks combinations CLI11 cannot: throws std::invalid_argument.
void checkTemporalOptions(const TemporalOptions& options, int spp);

}  // namespace tsr::app
