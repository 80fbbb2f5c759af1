#include "anaglyph_window.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <stdexcept>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include "glfw_start.hpp"

#include "anaglyph_options.hpp"
#include "tsr/med/image_file.hpp"
#include "tsr/sg/node_world.hpp"
#include "tsr/vk/swapchain_target.hpp"

namespace tsr::app {

namespace {

const sg::Camera& cameraOf(const SceneSession& session) { return *session.source.find<sg::Camera>(session.camera); }

// The orbit centre: the zero-parallax plane, where both eyes' images meet.
CameraNavigation navigationFor(const SceneSession& session, const StereoSettings& stereo) {
  return CameraNavigation(sg::cameraWorldPose(cameraOf(session)), stereo.zeroParallax);
}

char keyName(int key) {
  switch (key) {
    case GLFW_KEY_W:
      return 'w';
    case GLFW_KEY_A:
      return 'a';
    case GLFW_KEY_S:
      return 's';
    case GLFW_KEY_D:
      return 'd';
    case GLFW_KEY_Q:
      return 'q';
    case GLFW_KEY_E:
      return 'e';
    case GLFW_KEY_LEFT_BRACKET:
      return '[';
    case GLFW_KEY_RIGHT_BRACKET:
      return ']';
    case GLFW_KEY_MINUS:
      return '-';
    case GLFW_KEY_EQUAL:
      return '=';
    case GLFW_KEY_M:
      return 'm';
    case GLFW_KEY_R:
      return 'r';
    default:
      return 0;
  }
}

AnaglyphWindow* self(GLFWwindow* w) { return static_cast<AnaglyphWindow*>(glfwGetWindowUserPointer(w)); }

struct Pointer {
  double x = 0, y = 0;
  bool known = false;
} pointer;

// GLFW is initialised once per process and ended when its last window goes.
struct Glfw {
  Glfw() { app::startGlfw("no display? use --output FILE for a headless frame"); }
};

}  // namespace

AnaglyphWindow::AnaglyphWindow(SceneSession& session, StereoRenderer& renderer, StereoSettings stereo,
                               std::uint32_t width, std::uint32_t height, bool readback)
    : session_(session),
      renderer_(renderer),
      stereo_(stereo),
      initialStereo_(stereo),
      navigation_(navigationFor(session, stereo)),
      initialNavigation_(navigation_) {
  static Glfw glfw;
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
  window_ = glfwCreateWindow(static_cast<int>(width), static_cast<int>(height), "tessera-anaglyph", nullptr, nullptr);
  if (!window_)
    throw std::runtime_error("cannot open a " + std::to_string(width) + "x" + std::to_string(height) + " window");
  glfwSetWindowUserPointer(window_, this);
  glfwSetKeyCallback(window_, [](GLFWwindow* w, int key, int, int action, int) {
    if (action == GLFW_RELEASE) return;
    if (key == GLFW_KEY_ESCAPE) glfwSetWindowShouldClose(w, GLFW_TRUE);
    if (char name = keyName(key)) self(w)->key(name);
  });
  glfwSetCursorPosCallback(window_, [](GLFWwindow* w, double x, double y) {
    const bool orbit = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    const bool pan = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS ||
                     glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS;
    if (pointer.known && (orbit || pan)) self(w)->drag(x - pointer.x, y - pointer.y, pan);
    pointer = {x, y, true};
  });
  glfwSetScrollCallback(window_, [](GLFWwindow* w, double, double dy) { self(w)->scroll(dy); });
  glfwSetFramebufferSizeCallback(window_, [](GLFWwindow* w, int, int) { self(w)->dirty_ = true; });
  glfwSetWindowRefreshCallback(window_, [](GLFWwindow* w) { self(w)->dirty_ = true; });
  auto device = vk::Device::create(vk::DeviceOptions::forWindows());
  target_ = std::make_unique<vk::SwapchainTarget>(device, window_, vk::SwapchainOptions{.readback = readback});
}

AnaglyphWindow::~AnaglyphWindow() {
  target_.reset();
  if (window_) glfwDestroyWindow(window_);
}

void AnaglyphWindow::key(char name) {
  const float step = 0.05f;
  switch (name) {
    case 'w':
      navigation_.fly({0, 0, -step});
      moved_ = true;
      break;
    case 's':
      navigation_.fly({0, 0, step});
      moved_ = true;
      break;
    case 'a':
      navigation_.fly({-step, 0, 0});
      moved_ = true;
      break;
    case 'd':
      navigation_.fly({step, 0, 0});
      moved_ = true;
      break;
    case 'q':
      navigation_.fly({0, -step, 0});
      moved_ = true;
      break;
    case 'e':
      navigation_.fly({0, step, 0});
      moved_ = true;
      break;
    case '[':
      stereo_.separation /= 1.25f;
      break;
    case ']':
      stereo_.separation *= 1.25f;
      break;
    case '-':
      stereo_.zeroParallax /= 1.25f;
      break;
    case '=':
      stereo_.zeroParallax *= 1.25f;
      break;
    case 'm':
      stereo_.method =
          stereo_.method == med::AnaglyphMethod::Dubois ? med::AnaglyphMethod::RedCyan : med::AnaglyphMethod::Dubois;
      break;
    case 'r':
      navigation_ = initialNavigation_;
      stereo_ = initialStereo_;
      moved_ = true;
      break;
    default:
      return;
  }
  std::cout << "eye separation " << stereo_.separation << ", zero parallax " << stereo_.zeroParallax << ", "
            << methodName(stereo_.method) << std::endl;
  dirty_ = true;
}

void AnaglyphWindow::drag(double dx, double dy, bool pan) {
  int height = 0;
  glfwGetFramebufferSize(window_, nullptr, &height);
  const float perPixel = 1.0f / static_cast<float>(std::max(height, 1));
  if (pan)
    navigation_.pan(static_cast<float>(-dx) * perPixel, static_cast<float>(dy) * perPixel);
  else
    navigation_.orbit(static_cast<float>(-dx) * 0.25f, static_cast<float>(dy) * 0.25f);
  moved_ = dirty_ = true;
}

void AnaglyphWindow::scroll(double notches) {
  navigation_.dolly(static_cast<float>(notches));
  moved_ = dirty_ = true;
}

void AnaglyphWindow::frame() {
  int width = 0, height = 0;
  glfwGetFramebufferSize(window_, &width, &height);
  if (width <= 0 || height <= 0) return;  // minimised
  const auto started = std::chrono::steady_clock::now();
  if (moved_) sg::setCameraWorldPose(*session_.source.find<sg::Camera>(session_.camera), navigation_.pose());
  moved_ = false;
  renderer_.publish(session_);
  const auto view =
      med::View::fromCamera(cameraOf(session_), static_cast<std::uint32_t>(width), static_cast<std::uint32_t>(height));
  auto pair = renderer_.render(session_, view, stereo_.separation, stereo_.zeroParallax);
  shown_ = med::anaglyph(pair.left, pair.right, stereo_.method);
  target_->present(vk::FrameBuffer(shown_.width, shown_.height, shown_.colour));
  dirty_ = false;
  updateTitle(std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count());
}

void AnaglyphWindow::updateTitle(double seconds) {
  std::ostringstream title;
  title.precision(3);
  title << "tessera-anaglyph: " << methodName(stereo_.method) << ", eye separation " << stereo_.separation
        << ", zero parallax " << stereo_.zeroParallax << ", " << seconds << " s/frame";
  glfwSetWindowTitle(window_, title.str().c_str());
}

void AnaglyphWindow::run() {
  while (!glfwWindowShouldClose(window_)) {
    if (dirty_) frame();
    glfwWaitEventsTimeout(0.1);
  }
}

void AnaglyphWindow::run(const std::vector<WindowAction>& script) {
  for (const auto& a : script) {
    glfwPollEvents();
    switch (a.kind) {
      case WindowAction::Kind::Key:
        key(a.text[0]);
        break;
      case WindowAction::Kind::Orbit:
        drag(a.x, a.y, false);
        break;
      case WindowAction::Kind::Pan:
        drag(a.x, a.y, true);
        break;
      case WindowAction::Kind::Scroll:
        scroll(a.x);
        break;
      case WindowAction::Kind::Frames:
        for (int i = 0; i < static_cast<int>(a.x); ++i) {
          dirty_ = true;
          frame();
          glfwPollEvents();
        }
        break;
      case WindowAction::Kind::Screenshot:
        screenshot(a.text);
        break;
    }
  }
}

// What the window shows: the swapchain image read back, sRGB decoded, so
// the file is the window's pixels whatever the swapchain's channel order.
void AnaglyphWindow::screenshot(const std::string& path) const {
  const auto& bytes = target_->lastPresentedPixels();
  const std::uint32_t w = target_->lastPresentedWidth(), h = target_->lastPresentedHeight();
  if (bytes.size() != std::size_t{w} * h * 4 || w == 0)
    throw std::runtime_error("screenshot " + path + ": nothing shown yet (add 'frames 1' before it)");
  const bool bgra = target_->format() == VK_FORMAT_B8G8R8A8_SRGB || target_->format() == VK_FORMAT_B8G8R8A8_UNORM;
  auto decode = [](std::uint8_t v) {
    const float s = v / 255.0f;
    return s <= 0.04045f ? s / 12.92f : std::pow((s + 0.055f) / 1.055f, 2.4f);
  };
  med::FrameBuffer fb(w, h);
  for (std::size_t i = 0; i < fb.colour.size(); ++i) {
    const std::uint8_t* p = &bytes[i * 4];
    fb.colour[i] = glm::vec4(decode(p[bgra ? 2 : 0]), decode(p[1]), decode(p[bgra ? 0 : 2]), 1.0f);
  }
  med::writeImage(path, fb);
  std::cout << "wrote " << path << " (" << w << "x" << h << ")" << std::endl;
}

}  // namespace tsr::app
