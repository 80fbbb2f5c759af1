#include "tsr/temporal/pca_denoise.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>

#include "tsr/temporal/pca_basis.hpp"

namespace tsr::temporal {

double PcaResult::meanTruncation() const {
  if (truncation.empty()) return 0;
  return std::accumulate(truncation.begin(), truncation.end(), 0.0) / double(truncation.size());
}

PcaResult denoise(const std::vector<Frame>& frames, const PcaSettings& settings) {
  if (settings.fixedModes < 0) throw std::invalid_argument("temporal: a negative number of modes");
  if (!(settings.rule.epsilon >= 0 && settings.rule.epsilonChange >= 0 && settings.mapSigma >= 0))
    throw std::invalid_argument("temporal: epsilon, epsilon_change and the map's sigma must be >= 0");
  const PcaBasis basis(frames);
  PcaResult out;
  out.availableModes = basis.modes();
  if (settings.fixedModes > 0) {
    out.globalModes = std::min(settings.fixedModes, basis.modes());
  } else {
    out.globalModes = truncationFor(basis.unexplained(), settings.rule);
  }
  if (settings.fixedModes == 0 && settings.perPixel)
    out.truncation = truncationMap(basis, settings.rule, settings.mapSigma);
  else
    out.truncation.assign(frames.front().pixels(), static_cast<float>(out.globalModes));
  out.frames.reserve(frames.size());
  for (int t = 0; t < basis.modes(); ++t) out.frames.push_back(basis.reconstruct(t, out.truncation));
  return out;
}

}  // namespace tsr::temporal
