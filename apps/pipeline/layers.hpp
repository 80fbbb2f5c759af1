#pragma once
// tessera-render --layers: several viewports, possibly of different
// back-ends, layered in one window and composited by depth and alpha (e.g.
// the path-traced scene with rasterised markers on top).
//
// A layer is BACKEND or BACKEND:NODE, layers separated by commas, first
// layer at the bottom:
//   --layers embree                  the whole scene, path traced
//   --layers embree,vulkan:markers   plus the Group/Transform named exactly
//                                    "markers", rasterised on top
// A layer's root is the scene's root when no node is named, else the one
// Group or Transform with that name (an error if there is none or several).
// To keep a subtree out of the whole-scene layer, name disjoint roots
// (embree:box,vulkan:markers) or flag its geometry with the back-end's
// "<backend>.hidden" attachment.
// A value ending in .json is a file holding the same as an array, with
// per-layer parameters on top of the command line's:
//   [{"backend": "embree", "root": "box", "parameters": {"spp": 64}},
//    {"backend": "vulkan", "root": "markers", "parameters": {"msaa": 4}}]
// With --cluster, the one layer of the config's back-end renders on the
// nodes (cluster_layer.hpp), the others here.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "tsr/med/viewport_registry.hpp"
#include "tsr/med/window.hpp"
#include "tsr/sg/scene.hpp"

namespace tsr::app {

struct LayerSpec {
  std::string backend;
  std::string root;            // node name; empty: the scene's root
  med::Parameters parameters;  // on top of the command line's
};

// Parses the --layers value (or reads the .json file it names); throws
// std::invalid_argument with a one-line message.
std::vector<LayerSpec> parseLayers(const std::string& value);

// The Group or Transform named `name`; throws std::invalid_argument.
sg::ContainerId findLayerRoot(const sg::Scene& scene, const std::string& name);

// Makes the viewport of a layer rendered elsewhere (on a cluster's nodes);
// null: the layer renders here, through the registry.
using RemoteLayers = std::function<std::unique_ptr<med::Viewport>(const med::ViewportSettings&)>;

// A window with one viewport per layer; `defaults` gives the background,
// the scene's root and the command line's parameters. No layers: one layer
// of defaults.backend over the whole scene.
med::Window makeLayeredWindow(const std::vector<LayerSpec>& layers, const sg::Scene& scene,
                              const med::ViewportSettings& defaults, const med::ViewportRegistry& registry,
                              med::ContextPool& contexts, const RemoteLayers& remote = {});
// Throws std::invalid_argument naming what is offered when no layer of the
// window can fill one of `outputs` (colour and depth always can).
void checkOutputsOffered(const std::vector<std::string>& outputs, const med::Window& window);
// Renders the window; stats add up over the layers.
med::RenderStats renderLayered(med::Window& window, const sg::Replica& replica, const med::View& view,
                               med::FrameBuffer& out, const med::RenderControl& control);

}  // namespace tsr::app
