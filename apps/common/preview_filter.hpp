#pragma once
// The noise filter the programs people look at open with (tessera-viewer,
// tessera-wall, tessera-anaglyph): the path tracer's preview is the point
// of the project, so it is on unless `--param filter=none` turns it off.
// Pixel filtering is the best filter of the quality suite by the seen
// error (docs/filtering.md). Back-ends that declare no filter never get it.
#include <string>

#include "tsr/med/parameter_table.hpp"

namespace tsr::app {

inline constexpr const char* kPreviewFilter = "pixel";

// Sets the filter parameter to kPreviewFilter unless the user gave one or
// the back-end's table has no filter. Without a table (options for every
// viewport of a program), viewports whose back-end has none never get it
// (med::ViewportRegistry::parametersFor).
inline void usePreviewFilterUnlessSet(med::Parameters& parameters, const med::ParameterTable* backend = nullptr) {
  if ((!backend || backend->declares("filter")) && !parameters.has("filter"))
    parameters.set("filter", std::string(kPreviewFilter));
}

// The line a program prints at start, so a person knows what they see.
inline std::string previewFilterLine(const med::Parameters& parameters) {
  auto given = parameters.all().find("filter");
  const std::string* named = given == parameters.all().end() ? nullptr : std::get_if<std::string>(&given->second);
  const std::string filter = named ? *named : "none";
  return "path tracer preview filter: " + filter +
         (filter == "none" ? " (--param filter=" + std::string(kPreviewFilter) + " turns it on)"
                           : " (--param filter=none turns it off)");
}

}  // namespace tsr::app
