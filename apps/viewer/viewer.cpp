#include "viewer.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <imgui.h>
#include <spdlog/spdlog.h>
#include "glfw_start.hpp"

#include "backends.hpp"
#include "cluster/cluster_connection.hpp"
#include "imgui_overlay.hpp"
#include "tsr/cluster/cluster_viewport.hpp"
#include "tsr/med/coverage/ranking.hpp"
#include "tsr/sg/import/scene_stats.hpp"
#include "tsr/vk/device.hpp"
#include "tsr/vk/swapchain_target.hpp"

namespace tsr::app {

namespace {

// The camera counts as moving this long after its last change (figure 5.6's
// switch back to path tracing waits for the hand to rest).
constexpr auto kMovingFor = std::chrono::milliseconds(250);

Viewer* viewerOf(GLFWwindow* window) { return static_cast<Viewer*>(glfwGetWindowUserPointer(window)); }

}  // namespace

Viewer::Viewer(ViewerOptions options) : options_(std::move(options)), contexts_(std::make_unique<med::ContextPool>()) {
  registerBackends(registry_);
  for (const auto& backend : options_.viewports)
    if (!registry_.has(backend)) {
      med::ViewportSettings unknown;
      unknown.backend = backend;
      registry_.create(unknown, *contexts_);  // throws, naming the back-ends it knows
    }
  registry_.requireDeclared(options_.parameters, registry_.backends());  // a typo fails here, naming them
  convergence_.sampleLimit = options_.sampleLimit;
  convergence_.rasterWhileMoving = options_.rasterWhileMoving;
  showPanels_ = !options_.hidePanels;
  if (!options_.script.empty()) {
    ScriptLimits limits{std::uint32_t(options_.viewports.size()), registry_.backends()};
    script_ = parseScript(options_.script, limits);
    for (const auto& a : script_) needsWindowReadback_ |= a.verb == "window-screenshot";
  }
  med::ViewportSettings defaults;
  defaults.parameters = options_.parameters;
  for (const auto& backend : options_.viewports) panes_.emplace_back(backend, defaults);
  loadScene(options_.scene);
  if (!options_.cluster.empty()) connectToCluster();
}

// --cluster: viewport 0 renders on the nodes whenever it shows their
// back-end (its other back-ends render here); tessera-render's connection code.
void Viewer::connectToCluster() {
  RenderJob render;
  render.sequence.cluster = options_.cluster;
  render.sequence.nodes = options_.nodes;
  render.sequence.tokenFile = options_.tokenFile;
  render.parameters = options_.parameters;  // the config's own parameters win over these defaults
  const cluster::ClusterConfig config = clusterConfig(render);
  // The workload image (who rendered which tile) comes with every frame of
  // a cooperative or mono wall cluster; the O key shows it over the image.
  std::vector<std::string> outputs;
  if (config.mode == cluster::ClusterMode::Cooperative ||
      (config.mode == cluster::ClusterMode::Tiled && !config.wall.stereo()))
    outputs.emplace_back(cluster::kWorkloadOutput);
  std::shared_ptr<cluster::ClusterWindow> window = connectCluster(config, render, outputs, registry_);
  const auto* camera = session_->source.find<sg::Camera>(session_->camera);
  window->setEyes(camera->eyeSeparation(), camera->zeroParallaxDistance());
  cluster_ = window;
  const std::string backend = config.nodes.front().backend;
  panes_.front().setRemote(
      [window, backend, outputs](const med::ViewportSettings& settings) -> std::unique_ptr<med::Viewport> {
        if (settings.backend != backend) return nullptr;
        return std::make_unique<cluster::ClusterViewport>(settings, window, outputs);
      });
}

Viewer::~Viewer() {
  panes_.clear();  // viewports before the device and the window
  target_.reset();
  overlay_.reset();
  device_.reset();
  if (window_) glfwDestroyWindow(window_);
  glfwTerminate();
}

void Viewer::loadScene(const std::string& scene) {
  auto next = std::make_unique<SceneSession>();
  next->load(scene, options_.import);
  BookmarkFile marks;
  std::string markMessage;
  try {
    marks.load(BookmarkFile::pathFor(scene));
    if (!marks.bookmarks.empty())
      markMessage = std::to_string(marks.bookmarks.size()) + " bookmarks from " + marks.path;
  } catch (const BookmarkError& e) {
    marks.path = BookmarkFile::pathFor(scene);
    marks.loadError = e.what();
    markMessage = std::string("bookmarks not restored: ") + e.what();
  }
  // From here on nothing throws: the old scene goes.
  med::ViewportSettings defaults;
  defaults.root = next->imported.root;
  defaults.background = next->imported.background;
  for (auto& pane : panes_) pane.resetScene(defaults);
  contexts_ = std::make_unique<med::ContextPool>();
  session_ = std::move(next);
  sceneName_ = scene;
  bookmarks_ = std::move(marks);
  bookmarkMessage_ = markMessage;
  selected_ = sg::kNoContainer;
  animationTime_ = 0;
  animationDuration_ = 0;
  for (const auto& a : session_->imported.animations)
    animationDuration_ = std::max<double>(animationDuration_, a.duration());
  playing_ = animationDuration_ > 0;

  const auto stats = sg::computeSceneStats(session_->source, session_->imported.root);
  const glm::vec3 lo = stats.hasBounds ? stats.boundsMin : glm::vec3(-1),
                  hi = stats.hasBounds ? stats.boundsMax : glm::vec3(1);
  centre_ = (lo + hi) * 0.5f;
  radius_ = std::max(glm::length(hi - lo) * 0.5f, 1e-3f);
  orbit_.reset(*session_->source.find<sg::Camera>(session_->camera), centre_, radius_);
  session_->publish();
  sceneChanged_ = true;
  spdlog::info("tessera-viewer: opened {}", scene);
}

void Viewer::frameScene() {
  orbit_.frame(centre_, radius_, session_->source.find<sg::Camera>(session_->camera)->verticalFov());
}

void Viewer::openWindow() {
  app::startGlfw("is DISPLAY set? under no display, run through xvfb-run -a");
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
  window_ = glfwCreateWindow(int(options_.width), int(options_.height), "tessera-viewer", nullptr, nullptr);
  if (!window_)
    throw std::runtime_error("cannot open a window of " + std::to_string(options_.width) + "x" +
                             std::to_string(options_.height));
  glfwSetWindowUserPointer(window_, this);
  // Set before ImGui installs its callbacks, which chain to these.
  glfwSetDropCallback(window_, [](GLFWwindow* w, int count, const char** paths) {
    if (count > 0) viewerOf(w)->dropped_ = std::string(paths[0]);
  });
  glfwSetKeyCallback(window_, [](GLFWwindow* w, int key, int, int action, int) {
    auto& keys = viewerOf(w)->pressedKeys_;
    if (action == GLFW_PRESS && keys.size() < 64) keys.push_back(key);
  });
  // The presentation device is apart from the back-ends' (vk::sharedDevice):
  // it needs the window system's extensions; it only copies and draws panels.
  device_ = vk::Device::create(vk::DeviceOptions::forWindows(options_.validate));
  overlay_ = std::make_unique<ImGuiOverlay>(device_, window_);
  vk::SwapchainOptions swapchain;
  swapchain.overlay = overlay_.get();
  swapchain.readback = needsWindowReadback_;
  target_ = std::make_unique<vk::SwapchainTarget>(device_, window_, swapchain);
}

std::uint32_t Viewer::paneWidth(std::uint32_t windowWidth) const {
  return std::max<std::uint32_t>(windowWidth / std::uint32_t(panes_.size()), 1);
}

int Viewer::paneAt(double x) const {
  if (width_ == 0 || x < 0) return -1;
  const int i = int(x / paneWidth(width_));
  return i < int(panes_.size()) ? i : -1;
}

void Viewer::cycleBackend(std::size_t pane) {
  const auto names = registry_.backends();
  auto it = std::find(names.begin(), names.end(), panes_[pane].backend());
  const std::string next = it == names.end() || std::next(it) == names.end() ? names.front() : *std::next(it);
  panes_[pane].setBackend(next);
}

void Viewer::handleInput() {
  ImGuiIO& io = ImGui::GetIO();
  double x = 0, y = 0;
  glfwGetCursorPos(window_, &x, &y);
  const float dx = float(x - mouse_.x), dy = float(y - mouse_.y);
  mouse_.x = x;
  mouse_.y = y;
  auto* camera = session_->source.find<sg::Camera>(session_->camera);
  const float fov = camera->verticalFov();
  if (!io.WantCaptureMouse) {
    const bool left = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    const bool right = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS ||
                       glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS;
    const bool shift = glfwGetKey(window_, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS;
    if (ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
      mouse_.pressX = x;
      mouse_.pressY = y;
    }
    if (left && !shift) orbit_.orbit(-dx * 0.3f, dy * 0.3f);
    if (right || (left && shift))
      orbit_.pan(-dx / float(std::max(height_, 1u)), dy / float(std::max(height_, 1u)), fov);
    if (io.MouseWheel != 0.0f) orbit_.zoom(std::pow(0.9f, io.MouseWheel));
    // A click that did not drag picks the object under it (coverage viewports).
    if (ImGui::IsMouseReleased(ImGuiMouseButton_Left) && std::abs(x - mouse_.pressX) < 3 &&
        std::abs(y - mouse_.pressY) < 3) {
      const int pane = paneAt(x);
      const bool ctrl = glfwGetKey(window_, GLFW_KEY_LEFT_CONTROL) == GLFW_PRESS ||
                        glfwGetKey(window_, GLFW_KEY_RIGHT_CONTROL) == GLFW_PRESS;
      const std::uint32_t px = std::uint32_t(x) - std::uint32_t(pane) * paneWidth(width_);
      if (pane >= 0 && y >= 0) {
        if (ctrl)  // Ctrl+click focuses the lens there
          focusOn(std::size_t(pane), px, std::uint32_t(y));
        else
          pick(std::size_t(pane), px, std::uint32_t(y));
      }
    }
  }
  std::vector<int> pressed;
  pressed.swap(pressedKeys_);
  if (io.WantCaptureKeyboard) return;
  const float step = 0.02f;
  auto held = [&](int key) { return glfwGetKey(window_, key) == GLFW_PRESS ? 1.0f : 0.0f; };
  orbit_.fly((held(GLFW_KEY_W) - held(GLFW_KEY_S)) * step, (held(GLFW_KEY_D) - held(GLFW_KEY_A)) * step,
             (held(GLFW_KEY_E) - held(GLFW_KEY_Q)) * step);
  for (const int key : pressed) {
    if (key == GLFW_KEY_F) frameScene();
    if (key == GLFW_KEY_B) {
      const int pane = paneAt(x);
      cycleBackend(pane >= 0 ? std::size_t(pane) : 0);
    }
    if (key == GLFW_KEY_SPACE) convergence_.paused = !convergence_.paused;
    if (key == GLFW_KEY_H) showPanels_ = !showPanels_;
    if (key == GLFW_KEY_O) showWorkload_ = !showWorkload_;
    if (key == GLFW_KEY_ESCAPE) glfwSetWindowShouldClose(window_, GLFW_TRUE);
    if (key == GLFW_KEY_F12 || key == GLFW_KEY_P) {
      ++screenshots_;
      try {
        for (std::size_t i = 0; i < panes_.size(); ++i)
          screenshotPane(i, "viewer-" + std::to_string(screenshots_) + "-" + std::to_string(i) + ".png");
      } catch (const std::exception& e) {
        status_ = std::string("error: ") + e.what();  // a key's failure is shown, not fatal
      }
    }
    if (key >= GLFW_KEY_1 && key <= GLFW_KEY_9 && std::size_t(key - GLFW_KEY_1) < bookmarks_.bookmarks.size())
      loadBookmark(bookmarks_.bookmarks[std::size_t(key - GLFW_KEY_1)].name);
  }
}

void Viewer::setShutter(float open, float close) {
  auto* camera = session_->source.find<sg::Camera>(session_->camera);
  camera->setShutterOpen(std::min(open, close));
  camera->setShutterClose(std::max(open, close));
  setAnimationTime(animationTime_);  // the motion over the frame follows the shutter
}

void Viewer::setAnimationTime(double seconds) {
  animationTime_ = seconds;
  session_->poseAnimations(seconds, kShutterFrameInterval);
}

void Viewer::renderPanes() {
  auto* camera = session_->source.find<sg::Camera>(session_->camera);
  const auto now = std::chrono::steady_clock::now();
  const double dt =
      lastFrame_.time_since_epoch().count() ? std::chrono::duration<double>(now - lastFrame_).count() : 0.0;
  lastFrame_ = now;
  if (playing_ && animationDuration_ > 0) setAnimationTime(std::fmod(animationTime_ + dt, animationDuration_));
  // After the animations: the camera's world pose undoes this frame's
  // transforms above it, not the last frame's.
  if (orbit_.apply(*camera)) {
    lastMove_ = now;
    framesSinceMove_ = 0;
  }
  ++framesSinceMove_;
  // Only frames with edits are published: the replica's change log keeps
  // the last 256 lists, and a viewport switched back to catches up from it.
  const bool edited = sceneChanged_ || session_->source.hasPendingChanges();
  if (session_->source.hasPendingChanges()) session_->publish();
  sceneChanged_ = false;
  convergence_.cameraMoving = now - lastMove_ < kMovingFor;

  const auto* shown = session_->replica.scene().find<sg::Camera>(session_->camera);
  const std::uint32_t pw = paneWidth(width_);
  for (auto& pane : panes_) {
    const med::View view = med::View::fromCamera(*shown, pw, std::max(height_, 1u));
    try {
      pane.render(registry_, *contexts_, session_->replica, view, edited, convergence_);
      if (edited) pane.keepUp(session_->replica);
    } catch (const med::ParameterError& e) {
      status_ = std::string("error: ") + e.what();  // a bad setting from the panel: say so, keep going
    }
  }
  // What a switch cost, for people and tests: "synced" means nothing was converted again.
  for (std::size_t i = 0; i < panes_.size(); ++i)
    if (auto report = panes_[i].takeSwitchReport()) {
      const char* how = report->second.update == med::SceneAdapter::Update::Converted ? "converted"
                        : report->second.update == med::SceneAdapter::Update::Synced  ? "synced"
                                                                                      : "up to date";
      std::cout << "viewport " << i << ": " << report->first << ", scene " << how << " in "
                << report->second.syncSeconds << " s" << std::endl;
    }
}

void Viewer::present() {
  const std::uint32_t pw = paneWidth(width_);
  std::vector<glm::vec4> image(std::size_t(width_) * height_, glm::vec4(0, 0, 0, 1));
  for (std::size_t i = 0; i < panes_.size(); ++i) {
    const med::FrameBuffer& fb = panes_[i].frame();
    const auto* ids = fb.outputs.count(med::kIdOutput) ? &fb.outputs.at(med::kIdOutput) : nullptr;
    const std::string workloadName(cluster::kWorkloadOutput);
    const auto* workload =
        showWorkload_ && panes_[i].isRemote(panes_[i].shownBackend()) && fb.outputs.count(workloadName)
            ? &fb.outputs.at(workloadName)
            : nullptr;
    const std::uint32_t x0 = std::uint32_t(i) * pw;
    for (std::uint32_t y = 0; y < std::min(fb.height, height_); ++y)
      for (std::uint32_t x = 0; x < std::min(fb.width, width_ - std::min(x0, width_)); ++x) {
        glm::vec4 c = fb.colour[fb.index(x, y)];
        // The selected object stands out in coverage viewports; the rest dims.
        if (ids && selected_ != sg::kNoContainer) {
          const glm::vec4 id = (*ids)[fb.index(x, y)];
          const bool hit = id.a > 0 && med::decodeObjectId(id) == selected_;
          c = hit ? glm::mix(c, glm::vec4(1.0f), 0.5f) : c * 0.35f;
        }
        // Which node rendered the pixel's tile, half over the image (figure 5.8).
        if (workload) c = glm::mix(c, (*workload)[fb.index(x, y)], 0.5f);
        image[std::size_t(y) * width_ + x0 + x] = glm::vec4(glm::vec3(c), 1.0f);
      }
    if (i > 0)  // a dark seam between viewports
      for (std::uint32_t y = 0; y < height_; ++y) image[std::size_t(y) * width_ + x0] = glm::vec4(0.1f, 0.1f, 0.1f, 1);
  }
  target_->present(width_, height_, image);
}

int Viewer::run() {
  openWindow();
  while (!glfwWindowShouldClose(window_)) {
    // Nothing to converge, play or run: sleep until input (or a moment, for
    // ImGui's own animations) instead of spinning on the shared CPU.
    const bool busy = playing_ || scriptNext_ < script_.size() || framesToWait_ > 0 || samplesToWait_ > 0 ||
                      std::any_of(panes_.begin(), panes_.end(), [](const ViewerPane& p) { return p.converging(); }) ||
                      std::chrono::steady_clock::now() - lastMove_ < kMovingFor * 2;
    if (busy)
      glfwPollEvents();
    else
      glfwWaitEventsTimeout(0.1);
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    width_ = std::uint32_t(std::max(w, 0));
    height_ = std::uint32_t(std::max(h, 0));
    if (width_ == 0 || height_ == 0) {  // minimised
      glfwWaitEventsTimeout(0.1);
      continue;
    }
    if (dropped_) {
      const std::string path = *dropped_;
      dropped_.reset();
      try {
        loadScene(path);
        status_ = "opened " + path;
      } catch (const std::exception& e) {
        status_ = std::string("error: ") + e.what();  // the scene shown stays
      }
    }
    overlay_->beginFrame();
    handleInput();
    if (!runScript()) break;
    renderPanes();
    if (showPanels_) drawPanels();
    overlay_->endFrame();
    present();
    ++frame_;
  }
  if (options_.validate && device_->validationErrors() > 0) {
    const auto messages = device_->validationMessages();
    throw std::runtime_error(std::to_string(device_->validationErrors()) + " Vulkan validation errors, the first: " +
                             (messages.empty() ? std::string("?") : messages.front()));
  }
  return 0;
}

}  // namespace tsr::app
