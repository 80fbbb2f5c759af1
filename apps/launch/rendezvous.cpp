#include "rendezvous.hpp"

#include <sstream>

namespace tsr::app {

std::string missingRanksMessage(const std::vector<bool>& found, const std::string& where,
                                std::chrono::milliseconds timeout) {
  // found[i] is rank i + 1; at most 16 missing ranks are listed.
  std::string list;
  unsigned missing = 0, published = 0;
  for (std::size_t i = 0; i < found.size(); ++i) {
    if (found[i]) {
      ++published;
      continue;
    }
    if (missing < 16) list += (missing ? ", " : "") + std::to_string(i + 1);
    ++missing;
  }
  if (missing > 16) list += " and " + std::to_string(missing - 16) + " more";
  std::ostringstream s;
  s << (missing > 1 ? "ranks " : "rank ") << list << " published no address in " << where << " within "
    << timeout.count() / 1000.0 << " s (" << published << " of " << found.size() << " nodes did)";
  return s.str();
}

}  // namespace tsr::app
