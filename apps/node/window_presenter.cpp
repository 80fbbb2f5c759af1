#include "window_presenter.hpp"

#include <algorithm>
#include <chrono>
#include <stdexcept>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <spdlog/spdlog.h>
#include "glfw_start.hpp"

#include "tsr/vk/device.hpp"
#include "tsr/vk/swapchain_target.hpp"

namespace tsr::app {

void WindowPresenter::present(std::uint64_t frame, const std::vector<cluster::PresentedTile>& tiles,
                              const std::optional<cluster::WindowPlacement>& window) {
  if (tiles.empty()) return;
  // One screen is one rectangle; should a node hold several, it shows their bounding box.
  med::PixelRect box = tiles.front().rect;
  for (const auto& t : tiles) {
    box.x0 = std::min(box.x0, t.rect.x0);
    box.y0 = std::min(box.y0, t.rect.y0);
    box.x1 = std::max(box.x1, t.rect.x1);
    box.y1 = std::max(box.y1, t.rect.y1);
  }
  Pending p{frame, med::FrameBuffer(box.width(), box.height()), window};
  for (const auto& t : tiles)
    for (std::uint32_t y = 0; y < t.image.height; ++y)
      std::copy_n(t.image.colour.begin() + t.image.index(0, y), t.image.width,
                  p.image.colour.begin() + p.image.index(t.rect.x0 - box.x0, t.rect.y0 - box.y0 + y));
  {
    std::lock_guard lock(mutex_);
    pending_ = std::move(p);
  }
  wake_.notify_one();
}

bool WindowPresenter::run(const std::atomic<bool>& stop) {
  app::startGlfw("--present window needs a display: set DISPLAY, or present with --present none");
  struct Terminate {
    ~Terminate() { glfwTerminate(); }
  } terminate;
  auto device = vk::Device::create(vk::DeviceOptions::forWindows());
  GLFWwindow* window = nullptr;
  std::unique_ptr<vk::SwapchainTarget> target;
  std::optional<cluster::WindowPlacement> shownPlacement;
  std::uint32_t shownWidth = 0, shownHeight = 0;
  bool closed = false;
  while (!stop && !closed) {
    std::optional<Pending> next;
    {
      std::unique_lock lock(mutex_);
      wake_.wait_for(lock, std::chrono::milliseconds(16), [&] { return pending_.has_value(); });
      next.swap(pending_);
    }
    glfwPollEvents();
    if (window && glfwWindowShouldClose(window)) closed = true;
    if (!next || closed) continue;
    cluster::WindowPlacement place = next->placement.value_or(cluster::WindowPlacement{});
    std::uint32_t w = place.width ? place.width : next->image.width;
    std::uint32_t h = place.height ? place.height : next->image.height;
    if (!window || next->placement != shownPlacement || w != shownWidth || h != shownHeight) {
      target.reset();
      if (window) glfwDestroyWindow(window);
      glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
      glfwWindowHint(GLFW_DECORATED, place.fullscreen ? GLFW_FALSE : GLFW_TRUE);
      GLFWmonitor* monitor = place.fullscreen ? glfwGetPrimaryMonitor() : nullptr;
      window = glfwCreateWindow(static_cast<int>(w), static_cast<int>(h), title_.c_str(), monitor, nullptr);
      if (!window) throw std::runtime_error("--present window: cannot open a window");
      if (!monitor) glfwSetWindowPos(window, place.x, place.y);
      target = std::make_unique<vk::SwapchainTarget>(device, window);
      shownPlacement = next->placement;
      shownWidth = w;
      shownHeight = h;
      spdlog::info("window {}x{} at {},{}{}", w, h, place.x, place.y, place.fullscreen ? " (fullscreen)" : "");
    }
    vk::FrameBuffer fb(next->image.width, next->image.height, std::move(next->image.colour));
    if (!target->present(fb)) target->present(fb);  // an out-of-date swapchain is recreated and tried once more
    spdlog::debug("presented frame {}", next->frame);
  }
  target.reset();
  if (window) glfwDestroyWindow(window);
  return closed;
}

}  // namespace tsr::app
