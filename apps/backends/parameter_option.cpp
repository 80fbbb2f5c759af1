#include "parameter_option.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "backends.hpp"

namespace tsr::app {

namespace {
// A table's bound as an integer: infinite and beyond-int64 bounds clamp.
std::int64_t integerBound(double bound) {
  constexpr auto lo = std::numeric_limits<std::int64_t>::min(), hi = std::numeric_limits<std::int64_t>::max();
  if (bound <= double(lo)) return lo;
  if (bound >= double(hi)) return hi;
  return static_cast<std::int64_t>(bound);
}
}  // namespace

CLI::Option* addParameterOption(CLI::App& app, const std::string& option, const std::string& backend,
                                const std::string& parameter, std::int64_t& value) {
  const med::ViewportRegistry& registry = backendRegistry();
  const auto names = registry.backends();
  const med::ParameterSpec* spec = std::find(names.begin(), names.end(), backend) != names.end()
                                       ? registry.capabilities(backend).parameters.find(parameter)
                                       : nullptr;
  if (!spec || spec->type != med::ParameterType::Integer)
    throw std::logic_error(option + ": back-end '" + backend + "' declares no integer parameter '" + parameter + "'");
  value = std::get<std::int64_t>(spec->fallback);
  return app.add_option(option, value, spec->help)
      ->check(CLI::Range(integerBound(spec->min), integerBound(spec->max)))
      ->capture_default_str();
}

}  // namespace tsr::app
