// tessera-viewer: looks at a scene in a window, one or more viewports side
// by side, each with the back-end chosen at runtime. Errors: one line on
// stderr, exit status 2.
#include <algorithm>
#include <iostream>

#include <spdlog/spdlog.h>

#include "error_line.hpp"
#include "preview_defaults.hpp"
#include "viewer.hpp"
#include "viewer_options.hpp"

int main(int argc, char** argv) {
  spdlog::set_level(spdlog::level::warn);
  try {
    tsr::app::ViewerOptions options;
    if (!tsr::app::parseViewerOptions(argc, argv, options)) return 0;
    std::cout << tsr::app::previewDefaultsLine(options.parameters) << std::endl;
    tsr::app::Viewer viewer(std::move(options));
    return viewer.run();
  } catch (const std::exception& e) {
    tsr::app::printError(e.what());
    return 2;
  }
}
