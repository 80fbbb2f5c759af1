#include "layers.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "outputs/stats_json.hpp"

namespace tsr::app {

namespace {
bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

LayerSpec parseLayer(const std::string& text) {
  LayerSpec layer;
  auto colon = text.find(':');
  layer.backend = text.substr(0, colon);
  if (colon != std::string::npos) {
    layer.root = text.substr(colon + 1);
    if (layer.root.empty()) throw std::invalid_argument("--layers: '" + text + "' names no node after ':'");
  }
  if (layer.backend.empty()) throw std::invalid_argument("--layers: a layer without a back-end in '" + text + "'");
  return layer;
}

med::ParameterValue parameterValue(const std::string& layer, const std::string& name, const nlohmann::json& v) {
  if (v.is_boolean()) return v.get<bool>();
  if (v.is_number_integer()) return v.get<std::int64_t>();
  if (v.is_number()) return v.get<double>();
  if (v.is_string()) return v.get<std::string>();
  throw std::invalid_argument("--layers: layer " + layer + ": parameter " + name +
                              " must be a boolean, number or string");
}

std::vector<LayerSpec> readLayerFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::invalid_argument("--layers: cannot read " + path);
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument("--layers: " + path + ": " + e.what());
  }
  if (!doc.is_array() || doc.empty())
    throw std::invalid_argument("--layers: " + path + ": expected a non-empty array of layers");
  std::vector<LayerSpec> layers;
  for (std::size_t i = 0; i < doc.size(); ++i) {
    const auto& j = doc[i];
    const std::string where = path + " layer " + std::to_string(i);
    if (!j.is_object() || !j.contains("backend") || !j["backend"].is_string())
      throw std::invalid_argument("--layers: " + where + ": expected an object with a \"backend\" string");
    for (const auto& [key, value] : j.items())  // a misspelt key would otherwise be ignored
      if (key != "backend" && key != "root" && key != "parameters")
        throw std::invalid_argument("--layers: " + where + ": unknown key \"" + key +
                                    "\" (a layer takes backend, root, parameters)");
    LayerSpec layer;
    layer.backend = j["backend"].get<std::string>();
    if (j.contains("root")) {
      if (!j["root"].is_string()) throw std::invalid_argument("--layers: " + where + ": \"root\" must be a string");
      layer.root = j["root"].get<std::string>();
    }
    if (j.contains("parameters")) {
      if (!j["parameters"].is_object())
        throw std::invalid_argument("--layers: " + where + ": \"parameters\" must be an object");
      for (const auto& [name, value] : j["parameters"].items())
        layer.parameters.set(name, parameterValue(where, name, value));
    }
    layers.push_back(std::move(layer));
  }
  return layers;
}
}  // namespace

std::vector<LayerSpec> parseLayers(const std::string& value) {
  if (endsWith(value, ".json")) return readLayerFile(value);
  std::vector<LayerSpec> layers;
  std::stringstream in(value);
  for (std::string item; std::getline(in, item, ',');) layers.push_back(parseLayer(item));
  if (layers.empty() || value.back() == ',')
    throw std::invalid_argument("--layers: expected BACKEND[:NODE],... got '" + value + "'");
  return layers;
}

sg::ContainerId findLayerRoot(const sg::Scene& scene, const std::string& name) {
  sg::ContainerId found = sg::kNoContainer;
  for (auto id : scene.ids()) {
    const sg::Container* c = scene.find(id);
    if (c->name() != name || !sg::isParentType(c->type())) continue;
    if (found != sg::kNoContainer)
      throw std::invalid_argument("--layers: several groups or transforms are named '" + name + "'");
    found = id;
  }
  if (found == sg::kNoContainer) throw std::invalid_argument("--layers: no group or transform is named '" + name + "'");
  return found;
}

med::Window makeLayeredWindow(const std::vector<LayerSpec>& layers, const sg::Scene& scene,
                              const med::ViewportSettings& defaults, const med::ViewportRegistry& registry,
                              med::ContextPool& contexts, const RemoteLayers& remote) {
  med::Window window;
  // Options given for the whole window (--spp, --param) reach each layer
  // whose back-end takes them; one that no layer's back-end takes is an error.
  std::vector<std::string> backends;
  for (const LayerSpec& layer : layers) backends.push_back(layer.backend);
  if (layers.empty()) backends.push_back(defaults.backend);
  registry.requireDeclared(defaults.parameters, backends);
  auto add = [&](med::ViewportSettings settings) {
    settings.parameters = registry.parametersFor(settings.backend, settings.parameters);
    std::unique_ptr<med::Viewport> viewport = remote ? remote(settings) : nullptr;
    window.addLayer(viewport ? std::move(viewport) : registry.create(settings, contexts));
  };
  if (layers.empty()) add(defaults);
  for (const LayerSpec& layer : layers) {
    med::ViewportSettings settings = defaults;
    settings.backend = layer.backend;
    if (!layer.root.empty()) settings.root = findLayerRoot(scene, layer.root);
    for (const auto& [name, value] : layer.parameters.all()) settings.parameters.set(name, value);
    add(settings);
  }
  return window;
}

void checkOutputsOffered(const std::vector<std::string>& outputs, const med::Window& window) {
  std::vector<std::string> offered;
  for (const auto& layer : window.layers())
    for (auto& name : layer->outputNames()) offered.push_back(std::move(name));
  for (const std::string& output : outputs) {
    if (med::isColourOutput(output) || med::isDepthOutput(output) ||
        std::find(offered.begin(), offered.end(), output) != offered.end())
      continue;
    std::string list = "colour, depth";
    for (const std::string& name : offered) list += ", " + name;
    throw std::invalid_argument("--aov " + output + ": no such output here (offered: " + list + ")");
  }
}

med::RenderStats renderLayered(med::Window& window, const sg::Replica& replica, const med::View& view,
                               med::FrameBuffer& out, const med::RenderControl& control) {
  out = window.render(replica, view, control);
  med::RenderStats total;
  for (const auto& s : window.lastStats()) addStats(total, s);
  return total;
}

}  // namespace tsr::app
