#include "backends.hpp"

// registerBackends, one call per back-end the build has (TSR_BACKENDS).
#include "registered_backends.inc"

namespace tsr::app {

const med::ViewportRegistry& backendRegistry() {
  // Filled in place: factories may refer to the registry they are in.
  static med::ViewportRegistry registry;
  [[maybe_unused]] static const bool filled = (registerBackends(registry), true);
  return registry;
}

std::string backendChoices() {
  const std::vector<std::string> names = backendRegistry().backends();
  std::string text;
  for (std::size_t i = 0; i < names.size(); ++i)
    text += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
  return text;
}

}  // namespace tsr::app
