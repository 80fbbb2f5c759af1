#include "tsr/med/viewport_registry.hpp"

namespace tsr::med {

const BackendCapabilities Viewport::kUndeclared{};

void ViewportRegistry::add(const std::string& backend, const BackendCapabilities& capabilities, Factory factory) {
  entries_[backend] = {&capabilities, std::move(factory)};
}

const ViewportRegistry::Entry& ViewportRegistry::entry(const std::string& backend) const {
  auto it = entries_.find(backend);
  if (it == entries_.end()) {
    std::string known;
    for (const auto& [name, e] : entries_) known += (known.empty() ? "" : ", ") + name;
    throw UnknownBackend("unknown back-end '" + backend + "' (known: " + (known.empty() ? "none" : known) + ")");
  }
  return it->second;
}

std::unique_ptr<Viewport> ViewportRegistry::create(ViewportSettings settings, ContextPool& contexts) const {
  const Entry& e = entry(settings.backend);
  e.capabilities->parameters.validate(settings.parameters);
  std::unique_ptr<Viewport> viewport = e.factory(std::move(settings), contexts);
  viewport->capabilities_ = e.capabilities;
  return viewport;
}

const BackendCapabilities& ViewportRegistry::capabilities(const std::string& backend) const {
  return *entry(backend).capabilities;
}

Parameters ViewportRegistry::parametersFor(const std::string& backend, const Parameters& offered) const {
  const ParameterTable& table = capabilities(backend).parameters;
  Parameters kept;
  for (const auto& [name, value] : offered.all())
    if (table.declares(name)) kept.set(name, value);
  return kept;
}

void ViewportRegistry::requireDeclared(const Parameters& given, const std::vector<std::string>& backends) const {
  for (const auto& [name, value] : given.all()) {
    const ParameterTable* declaring = nullptr;
    for (const auto& b : backends)
      if (capabilities(b).parameters.declares(name)) declaring = &capabilities(b).parameters;
    if (declaring) {
      declaring->validate(name, value);
    } else if (backends.size() == 1) {
      capabilities(backends.front()).parameters.validate(name, value);  // names what it takes
    } else {
      std::string all, typo;
      for (const auto& b : backends) {
        all += (all.empty() ? "" : ", ") + b;
        if (const ParameterSpec* near = capabilities(b).parameters.nearest(name); near && typo.empty())
          typo = " (did you mean " + near->name + ", which " + b + " takes?)";
      }
      throw UnknownParameter("unknown parameter '" + name + "'" + typo + ": none of the back-ends " + all +
                             " takes it (tessera-render --list-params BACKEND lists theirs)");
    }
  }
}

void ViewportRegistry::addBouncedLight(const std::string& backend, BouncedLightFactory factory) {
  bouncedLights_[backend] = std::move(factory);
}

std::shared_ptr<BouncedLight> ViewportRegistry::bouncedLight(sg::ContainerId root, sg::ContainerId background,
                                                             ContextPool& contexts) const {
  if (bouncedLights_.empty()) return nullptr;
  return bouncedLights_.begin()->second(root, background, contexts);
}

std::vector<std::string> ViewportRegistry::backends() const {
  std::vector<std::string> names;
  for (const auto& [name, e] : entries_) names.push_back(name);
  return names;
}

}  // namespace tsr::med
