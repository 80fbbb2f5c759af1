#pragma once
// How the programs people look at open the path tracer's preview
// (tessera-viewer, tessera-wall, tessera-anaglyph, the cull service's
// browser previews): the preview is the point of the project, so its noise
// filter and its history are on unless `--param filter=none` or
// `--param history=false` turns them off.
// - Pixel filtering is the best filter of the quality suite by the seen
//   error (docs/filtering.md), and on a moving camera with the history too
//   (docs/viewer.md).
// - The history (temporal reprojection) keeps the samples of what stays in
//   view while the camera or objects move, instead of restarting at each
//   change (docs/viewer.md measures it on an orbit).
// Back-ends that declare neither parameter never get them.
#include <string>

#include "tsr/med/parameter_table.hpp"

namespace tsr::app {

inline constexpr const char* kPreviewFilter = "pixel";

// Sets the filter parameter to kPreviewFilter and history to true, each
// unless the user gave it or the back-end's table does not declare it.
// Without a table (options for every viewport of a program), viewports whose
// back-end has none never get them (med::ViewportRegistry::parametersFor).
inline void usePreviewDefaultsUnlessSet(med::Parameters& parameters, const med::ParameterTable* backend = nullptr) {
  if ((!backend || backend->declares("filter")) && !parameters.has("filter"))
    parameters.set("filter", std::string(kPreviewFilter));
  if ((!backend || backend->declares("history")) && !parameters.has("history")) parameters.set("history", true);
}

// The line a program prints at start, so a person knows what they see.
inline std::string previewDefaultsLine(const med::Parameters& parameters) {
  auto given = parameters.all().find("filter");
  const std::string* named = given == parameters.all().end() ? nullptr : std::get_if<std::string>(&given->second);
  const std::string filter = named ? *named : "none";
  auto history = parameters.all().find("history");
  const bool* on = history == parameters.all().end() ? nullptr : std::get_if<bool>(&history->second);
  return "path tracer preview filter: " + filter +
         (filter == "none" ? " (--param filter=" + std::string(kPreviewFilter) + " turns it on)"
                           : " (--param filter=none turns it off)") +
         "; history while moving: " + (on && *on ? "on (--param history=false turns it off)" : "off");
}

}  // namespace tsr::app
