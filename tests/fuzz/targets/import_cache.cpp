#include <algorithm>
#include <cstdlib>
#include <memory>
#include <stdexcept>

#include "cache/parsed_scene_codec.hpp"
#include "fuzz_targets.hpp"

namespace tsr::fuzz {

// An import cache entry's scene (the part after the checked header): it
// decodes and validates, or is refused with std::runtime_error; what it
// accepts encodes back to the same bytes.
// Both ways: the arrays copied, and used in place as a mapped entry's are
// (the keeper owns nothing here: the bytes outlive the scene).
void importCache(Bytes bytes) {
  const auto notOwned = std::shared_ptr<const void>(bytes.data(), [](const void*) {});
  for (const std::shared_ptr<const void>& keeper : {std::shared_ptr<const void>(), notOwned}) {
    sg::parsed::Scene scene;
    try {
      scene = sg::parsed::decodeScene(bytes, keeper);
    } catch (const std::runtime_error&) {
      return;
    }
    const std::vector<std::uint8_t> again = sg::parsed::encodeScene(scene);
    if (again.size() != bytes.size() || !std::equal(again.begin(), again.end(), bytes.begin())) std::abort();
  }
}

}  // namespace tsr::fuzz
