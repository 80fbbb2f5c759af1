#pragma once
// The noise filter the programs people look at open with (tessera-viewer,
// tessera-wall, tessera-anaglyph): the path tracer's preview is the point
// of the project, so it is on unless `--param filter=none` turns it off.
// Pixel filtering is the best filter of the quality suite by the seen
// error (docs/filtering.md). Other back-ends ignore the parameter.
#include <string>

#include "tsr/med/parameters.hpp"

namespace tsr::app {

inline constexpr const char* kPreviewFilter = "pixel";

// Sets the filter parameter to kPreviewFilter unless the user gave one.
inline void usePreviewFilterUnlessSet(med::Parameters& parameters) {
  if (!parameters.has("filter")) parameters.set("filter", std::string(kPreviewFilter));
}

// The line a program prints at start, so a person knows what they see.
inline std::string previewFilterLine(const med::Parameters& parameters) {
  const std::string filter = parameters.getString("filter", "none");
  return "path tracer preview filter: " + filter +
         (filter == "none" ? " (--param filter=" + std::string(kPreviewFilter) + " turns it on)"
                           : " (--param filter=none turns it off)");
}

}  // namespace tsr::app
