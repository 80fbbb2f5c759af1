#pragma once
// A region of a window rendered by one back-end: what to show (root,
// camera, background), back-end parameters, and whether it is active. The
// only way applications and the cluster reach a back-end.
#include <algorithm>
#include <atomic>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "tsr/med/frame_buffer.hpp"
#include "tsr/med/parameter_table.hpp"
#include "tsr/med/scene_adapter.hpp"
#include "tsr/med/view.hpp"

namespace tsr::med {

struct ViewportSettings {
  std::string backend;
  sg::ContainerId root = sg::kNoContainer;        // none: every root of the scene
  sg::ContainerId background = sg::kNoContainer;  // none: black
  Parameters parameters;
  bool active = true;
};

struct RenderControl {
  std::function<void(double fraction)> progress;  // 0..1 as the render proceeds
  const std::atomic<bool>* cancel = nullptr;      // stop early when set
  // The named outputs (FrameBuffer::outputs) the caller will read; a
  // back-end may then skip filling the others. Unset: all it offers.
  // Colour and depth are always filled.
  std::optional<std::vector<std::string>> outputs;
  // False where the frame is assembled from regions rendered apart (cluster
  // tiles): the viewport then leaves its whole-frame image steps undone and
  // returns their inputs (resolveInputs()) as named outputs instead.
  bool resolve = true;
  // The animation frame shown; viewports with a lookahead() need it. -1: none.
  std::int64_t frame = -1;
  // A frame of an interactive session that is drawn again and again (the
  // viewer): a back-end may show work still in progress rather than wait
  // for it (the rasterizer's bounced light traced again in turns after an
  // edit). False: the frame is finished when render returns, and the same
  // scene gives the same picture whatever came before (files, walls, eyes).
  bool interactive = false;

  bool wants(const std::string& output) const {
    return !outputs || std::find(outputs->begin(), outputs->end(), output) != outputs->end();
  }
};

struct RenderStats {
  std::uint64_t rays = 0;     // rays cast, for ray tracers
  std::uint32_t samples = 0;  // samples per pixel accumulated so far
  double seconds = 0;         // the whole render call
  double syncSeconds = 0;     // of which catching up: conversion and acceleration structures
  SceneAdapter::Update update = SceneAdapter::Update::None;  // what catching up took
};

// What a back-end can do, declared with it (ViewportRegistry::add) and
// asked of its viewports: callers never infer it from the back-end's name.
struct BackendCapabilities {
  ParameterTable parameters;
  // Renders of an unchanged view add samples to the image (RenderStats::
  // samples counts them); false: every render is final.
  bool progressive = false;
  // Renders the View's thin lens (depth of field); false: its pinhole.
  bool depthOfField = false;
  // Blurs what moves while the View's shutter is open; false: renders the
  // scene at the frame's time.
  bool motionBlur = false;
};

class Viewport {
 public:
  explicit Viewport(ViewportSettings settings) : settings_(std::move(settings)) {}
  virtual ~Viewport() = default;

  const ViewportSettings& settings() const { return settings_; }
  const std::string& backend() const { return settings_.backend; }
  bool active() const { return settings_.active; }
  void setActive(bool active) { settings_.active = active; }
  // Parameters may change between renders (a progressive image restarts
  // only when the change affects it). A name or value the back-end does not
  // take throws UnknownParameter or BadParameterValue, changing nothing.
  void setParameter(const std::string& name, ParameterValue value) {
    if (capabilities_ != &kUndeclared) capabilities_->parameters.validate(name, value);
    settings_.parameters.set(name, std::move(value));
  }
  // What the back-end can do; the named outputs it offers are outputNames().
  const BackendCapabilities& capabilities() const { return *capabilities_; }

  // Brings the back-end's scene up to the replica's version (the mediator's
  // part; back-ends may still build acceleration structures at render).
  virtual SceneAdapter::Update synchronize(const sg::Replica& replica) = 0;
  // Catches the back-end up with the replica, then renders the view's
  // region into `out` (resized to the region).
  virtual RenderStats render(const sg::Replica& replica, const View& view, FrameBuffer& out,
                             const RenderControl& control = {}) = 0;
  // The named outputs render() can fill, besides colour and depth.
  virtual std::vector<std::string> outputNames() const { return {}; }

  // Image-space steps that need the whole frame at once (pixel filtering
  // gathers from neighbours up to many pixels away). Whoever assembles a
  // frame from regions rendered elsewhere asks render() for these outputs
  // with RenderControl::resolve false, then calls resolve() on the
  // assembled frame: the result equals a whole-frame render's. Empty: the
  // back-end's regions are final as rendered.
  virtual std::vector<std::string> resolveInputs() const { return {}; }
  // Named outputs that resolve() makes (e.g. a filter's blend factors):
  // the assembler asks nodes for the others only.
  virtual std::vector<std::string> resolveOutputs() const { return {}; }
  virtual void resolve(FrameBuffer& /*frame*/) {}

  // Frames of an animation a viewport must see before it shows one: a
  // temporal method that gathers from the frames around the one shown
  // (photon density estimation over time) sees the future through a second
  // replica. The caller feeds every frame in order to prepare(), with a
  // replica posed at that frame, and renders frame f (RenderControl::frame)
  // once f + lookahead() was prepared or the animation has no more frames.
  // Zero: render() needs nothing ahead and prepare() does nothing.
  virtual std::uint32_t lookahead() const { return 0; }
  virtual void prepare(const sg::Replica& /*ahead*/, std::int64_t /*frame*/) {}

 protected:
  ViewportSettings settings_;

 private:
  friend class ViewportRegistry;
  // Set by the registry that made the viewport.
  const BackendCapabilities* capabilities_ = &kUndeclared;
  static const BackendCapabilities kUndeclared;
};

}  // namespace tsr::med
