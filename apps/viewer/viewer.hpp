#pragma once
// tessera-viewer's window: the scene session, the viewports side by side,
// navigation, the panels and the script. One thread: each frame polls
// input, runs at most one script action, publishes the frame's edits to the
// replica, renders every viewport's share of work, draws the panels and
// presents the composed image.
#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "camera_bookmarks.hpp"
#include "orbit_camera.hpp"
#include "scene/scene_session.hpp"
#include "tsr/med/viewport_registry.hpp"
#include "viewer_options.hpp"
#include "viewer_pane.hpp"
#include "viewer_script.hpp"

struct GLFWwindow;

namespace tsr::cluster {
class ClusterWindow;
}  // namespace tsr::cluster

namespace tsr::vk {
class Device;
class SwapchainTarget;
}  // namespace tsr::vk

namespace tsr::app {

class ImGuiOverlay;

class Viewer {
 public:
  // Loads the scene and the script (throws on bad input, before any window).
  explicit Viewer(ViewerOptions options);
  ~Viewer();
  // Opens the window and runs until it closes (or the script ends with
  // --exit-after). Returns the exit status.
  int run();

 private:
  struct Mouse {
    double x = 0, y = 0;
    bool dragging = false;
    double pressX = 0, pressY = 0;
  };

  void openWindow();
  void connectToCluster();
  void loadScene(const std::string& scene);  // replaces the session; throws, leaving the old one
  void frameScene();
  std::uint32_t paneWidth(std::uint32_t windowWidth) const;
  int paneAt(double x) const;

  void handleInput();
  bool runScript();  // false when the script asks for no more frames
  void runAction(const ScriptAction& action);
  void renderPanes();
  void drawPanels();
  // The parts of drawPanels (viewer_panels.cpp): the viewer's own panel and
  // its camera section, and one viewport's panel.
  void drawViewerPanel();
  void drawCameraSection();
  void drawPanePanel(std::size_t i, std::uint32_t pw);
  void present();

  void screenshotPane(std::size_t pane, const std::string& path);
  void screenshotWindow(const std::string& path);
  void pick(std::size_t pane, std::uint32_t x, std::uint32_t y);
  void focusOn(std::size_t pane, std::uint32_t x, std::uint32_t y);
  void report() const;
  void cycleBackend(std::size_t pane);
  void saveBookmark(const std::string& name);
  void loadBookmark(const std::string& name);
  // The camera's shutter (fractions of the frame interval), the animation
  // posed again so its motion follows.
  void setShutter(float open, float close);
  void setAnimationTime(double seconds);

  ViewerOptions options_;
  med::ViewportRegistry registry_;
  std::unique_ptr<med::ContextPool> contexts_;
  std::unique_ptr<SceneSession> session_;
  std::string sceneName_;
  glm::vec3 centre_{0.0f};
  float radius_ = 1.0f;
  OrbitCamera orbit_;
  std::vector<ViewerPane> panes_;
  ConvergenceSettings convergence_;
  std::vector<ScriptAction> script_;
  std::size_t scriptNext_ = 0;
  std::int64_t framesToWait_ = 0;
  std::int64_t samplesToWait_ = 0;
  bool needsWindowReadback_ = false;

  BookmarkFile bookmarks_;
  std::string bookmarkMessage_;
  std::string status_;  // the last error or notice, shown in the panel
  std::optional<std::string> dropped_;
  // Keys pressed since the last frame, from GLFW's callback: a tap shorter
  // than a (slow, path-traced) frame is not lost as it would be by polling.
  std::vector<int> pressedKeys_;
  sg::ContainerId selected_ = sg::kNoContainer;
  double animationTime_ = 0, animationDuration_ = 0;
  // The frame interval an open shutter's fractions refer to: the viewer's
  // frames come as fast as they render, so motion blur uses a nominal 30 fps.
  static constexpr double kShutterFrameInterval = 1.0 / 30.0;
  bool playing_ = false;
  bool sceneChanged_ = true;
  bool showPanels_ = true;
  // --cluster: the nodes' window, and whether viewport 0 shows which node
  // rendered which tile over its image (O, or the script's "workload on").
  std::shared_ptr<cluster::ClusterWindow> cluster_;
  bool showWorkload_ = false;
  std::chrono::steady_clock::time_point lastMove_{};
  std::uint64_t framesSinceMove_ = 0;  // rendered since lastMove_, that one included
  std::chrono::steady_clock::time_point lastFrame_{};
  std::uint64_t frame_ = 0;
  std::uint32_t screenshots_ = 0;
  Mouse mouse_;

  GLFWwindow* window_ = nullptr;
  std::shared_ptr<vk::Device> device_;
  std::unique_ptr<ImGuiOverlay> overlay_;
  std::unique_ptr<vk::SwapchainTarget> target_;
  std::uint32_t width_ = 0, height_ = 0;  // the window's framebuffer
};

}  // namespace tsr::app
