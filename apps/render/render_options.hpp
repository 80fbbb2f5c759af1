#pragma once
// tessera-render's command line, parsed and checked; nothing rendered yet.
#include <string>

#include "layers.hpp"
#include "render_job.hpp"

namespace tsr::app {

// Parses argv (every option is declared, so --help lists them all and an
// unknown one is an error); throws std::invalid_argument with a one-line
// message for bad input or options that cannot combine. Returns false when
// help was printed (exit 0). `listParams`: the back-end --list-params names.
bool parseRenderOptions(int argc, char** argv, RenderJob& job, std::string& listParams);

// Every check of options that cannot combine, once --layers is parsed; the
// pipeline checks only what depends on the scene (--temporal-space auto).
void checkRenderJob(const RenderJob& job, const std::vector<LayerSpec>& layers);

}  // namespace tsr::app
