#include "tsr/med/viewport_registry.hpp"

namespace tsr::med {

void ViewportRegistry::add(const std::string& backend, Factory factory) { factories_[backend] = std::move(factory); }

std::unique_ptr<Viewport> ViewportRegistry::create(ViewportSettings settings, ContextPool& contexts) const {
  auto it = factories_.find(settings.backend);
  if (it == factories_.end()) {
    std::string known;
    for (const auto& [name, f] : factories_) known += (known.empty() ? "" : ", ") + name;
    throw UnknownBackend("unknown back-end '" + settings.backend + "' (known: " + (known.empty() ? "none" : known) +
                         ")");
  }
  return it->second(std::move(settings), contexts);
}

std::vector<std::string> ViewportRegistry::backends() const {
  std::vector<std::string> names;
  for (const auto& [name, f] : factories_) names.push_back(name);
  return names;
}

}  // namespace tsr::med
