#pragma once
// The client's messages on /v1/preview, read and checked (a
// CullRequestError names the problem):
//   {"seq": N, "view": {"camera": {...}, "width": W, "height": H}}
//   {"seq": N, "stop": true}
#include <cstdint>
#include <optional>
#include <string>

#include "cull_query.hpp"

namespace tsr::app {

struct PreviewRequest {
  std::uint32_t seq = 0;
  std::optional<CullQuery> view;  // none: stop refining
};

PreviewRequest parsePreviewRequest(const std::string& text);
// Throws CullRequestError when the view has more pixels than a preview may.
void checkPreviewSize(const CullQuery& view, std::uint64_t maxPixels);

}  // namespace tsr::app
