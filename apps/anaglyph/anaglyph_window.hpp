#pragma once
// The anaglyph in a GLFW window presented through the Vulkan swapchain:
// mouse and keyboard move the scene camera (the edit travels to the
// renderers as a change list), keys adjust eye separation, zero-parallax
// distance and the method. A frame is rendered only when something changed.
#include <cstdint>
#include <memory>
#include <vector>

#include "camera_navigation.hpp"
#include "stereo_renderer.hpp"
#include "tsr/med/compositing.hpp"
#include "window_script.hpp"

struct GLFWwindow;

namespace tsr::vk {
class SwapchainTarget;
}

namespace tsr::app {

struct StereoSettings {
  float separation = 0.065f;
  float zeroParallax = 5.0f;
  med::AnaglyphMethod method = med::AnaglyphMethod::Dubois;
};

class AnaglyphWindow {
 public:
  // Opens the window (throws std::runtime_error without a display or Vulkan surface support).
  AnaglyphWindow(SceneSession& session, StereoRenderer& renderer, StereoSettings stereo, std::uint32_t width,
                 std::uint32_t height, bool readback);
  ~AnaglyphWindow();
  AnaglyphWindow(const AnaglyphWindow&) = delete;
  AnaglyphWindow& operator=(const AnaglyphWindow&) = delete;

  // Until the window is closed or Esc pressed.
  void run();
  // The actions, then return (a screenshot writes what the window last showed).
  void run(const std::vector<WindowAction>& script);

  // Input, from GLFW's callbacks and from scripts alike.
  void key(char name);
  void drag(double dx, double dy, bool pan);
  void scroll(double notches);

 private:
  void frame();
  void screenshot(const std::string& path) const;
  void updateTitle(double seconds);

  SceneSession& session_;
  StereoRenderer& renderer_;
  StereoSettings stereo_, initialStereo_;
  CameraNavigation navigation_, initialNavigation_;
  bool moved_ = false, dirty_ = true;
  GLFWwindow* window_ = nullptr;
  std::unique_ptr<vk::SwapchainTarget> target_;
  med::FrameBuffer shown_;
};

}  // namespace tsr::app
