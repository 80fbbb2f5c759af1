#include <algorithm>
#include <cstdlib>
#include <stdexcept>

#include "cache/parsed_scene_codec.hpp"
#include "fuzz_targets.hpp"

namespace tsr::fuzz {

// An import cache entry's scene (the part after the checked header): it
// decodes and validates, or is refused with std::runtime_error; what it
// accepts encodes back to the same bytes.
void importCache(Bytes bytes) {
  sg::parsed::Scene scene;
  try {
    scene = sg::parsed::decodeScene(bytes);
  } catch (const std::runtime_error&) {
    return;
  }
  const std::vector<std::uint8_t> again = sg::parsed::encodeScene(scene);
  if (again.size() != bytes.size() || !std::equal(again.begin(), again.end(), bytes.begin())) std::abort();
}

}  // namespace tsr::fuzz
