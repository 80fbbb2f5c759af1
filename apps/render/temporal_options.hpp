#pragma once
// tessera-render's temporal noise reduction options (with --frames):
//   --temporal pca|photons   denoise the indirect light over the sequence
//   --direct-spp N           samples of direct light per frame
//   --temporal-modes M       fixed PCA truncation (default: automatic, 2.3)
//   --temporal-epsilon E, --temporal-epsilon-change C, --temporal-global,
//   --temporal-map-sigma S, --temporal-window W, --temporal-overlap O
#include <CLI/CLI.hpp>

#include <string>

namespace tsr::app {

struct TemporalOptions {
  std::string method;  // empty: frame by frame
  int directSpp = 0;   // 0: the same as --spp (see --help)
  int modes = 0;       // 0: automatic
  double epsilon = 0.005, epsilonChange = 0.001;
  bool global = false;  // one truncation for the whole frame instead of 3.2's map
  double mapSigma = 2.0;
  int window = 64, overlap = 16;
  bool active() const { return !method.empty(); }
};

// Declares the options on `app` (so --help lists them), in their own group.
void addTemporalOptions(CLI::App& app, TemporalOptions& options);

// Checks combinations CLI11 cannot: throws std::invalid_argument.
void checkTemporalOptions(const TemporalOptions& options, int spp);

}  // namespace tsr::app
