#pragma once
// A command-line option that sets one of a back-end's integer parameters
// (--max-depth for maxDepth): its default, range and help are the
// back-end's table's, said once there.
#include <cstdint>
#include <string>

#include <CLI/CLI.hpp>

namespace tsr::app {

// Adds `option` to `app`, storing into `value` (set to the table's default).
// Throws std::logic_error when this build's `backend` declares no integer
// `parameter`.
CLI::Option* addParameterOption(CLI::App& app, const std::string& option, const std::string& backend,
                                const std::string& parameter, std::int64_t& value);

}  // namespace tsr::app
