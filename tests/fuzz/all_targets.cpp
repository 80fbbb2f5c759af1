#include "fuzz_targets.hpp"

namespace tsr::fuzz {

std::vector<Target> allTargets() {
  return {
      {"wire_codec", &wireCodec},
#ifdef TSR_FUZZ_HAVE_CLUSTER
      {"cluster_messages", &clusterMessages},
      {"pixel_codec", &pixelCodec},
      {"cluster_config", &clusterConfig},
#endif
#ifdef TSR_FUZZ_HAVE_IMPORT
      {"gltf_import", &gltfImport},
#endif
  };
}

}  // namespace tsr::fuzz
