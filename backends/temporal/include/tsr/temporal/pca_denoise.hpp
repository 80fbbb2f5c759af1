#pragma once
// Basis projection of a whole stack (Meyer & Anderson 2.4): PCA, a
// truncation (fixed, automatic, or per pixel), and the reconstruction.
#include <vector>

#include "tsr/temporal/frame.hpp"
#include "tsr/temporal/truncation.hpp"

namespace tsr::temporal {

struct PcaSettings {
  TruncationRule rule;
  int fixedModes = 0;     // > 0: keep this many modes everywhere (capped at N)
  bool perPixel = true;   // 3.2's truncation map (ignored with fixedModes)
  double mapSigma = 2.0;  // Gaussian smoothing of the map, pixels
};

struct PcaResult {
  std::vector<Frame> frames;      // reconstructed, one per input frame
  int globalModes = 0;            // 2.3's M for the whole stack (or the fixed one)
  std::vector<float> truncation;  // the per-pixel map used (all globalModes without one)
  int availableModes = 0;         // N: every mode of the stack (one per frame)
  double meanTruncation() const;
};

// Throws std::invalid_argument for an inconsistent stack or settings.
PcaResult denoise(const std::vector<Frame>& frames, const PcaSettings& settings);

}  // namespace tsr::temporal
