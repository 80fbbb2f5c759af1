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
      {"import_cache", &importCache},
#endif
#ifdef TSR_FUZZ_HAVE_LAUNCH
      {"launch_address_file", &launchAddressFile},
      {"launch_rank_line", &launchRankLine},
#endif
#ifdef TSR_FUZZ_HAVE_VIEWER
      {"viewer_script", &viewerScript},
      {"camera_bookmarks", &cameraBookmarks},
#endif
#ifdef TSR_FUZZ_HAVE_ANAGLYPH
      {"anaglyph_script", &anaglyphScript},
#endif
#ifdef TSR_FUZZ_HAVE_CULL
      {"cull_http_request", &cullHttpRequest},
      {"cull_preview_message", &cullPreviewMessage},
#endif
  };
}

}  // namespace tsr::fuzz
