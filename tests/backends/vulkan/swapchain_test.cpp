// Presenting to a GLFW window. Needs an X display: ctest runs this binary
// through `xvfb-run -a` with TSR_REQUIRE_DISPLAY=1 (tests/backends/vulkan/
// CMakeLists.txt), so on CI a missing display fails rather than skips.
#include "test_util.hpp"

#include "tsr/vk/renderer.hpp"
#include "tsr/vk/scene.hpp"
#include "tsr/vk/swapchain_target.hpp"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <thread>

namespace tsr::vk {
namespace {

bool displayRequired() {
  const char* v = std::getenv("TSR_REQUIRE_DISPLAY");
  return v && *v && std::string(v) != "0";
}

class VulkanSwapchain : public ::testing::Test {
 protected:
  // The previous test's disconnect may find Xvfb briefly refusing new
  // clients (a server reset when xvfb-run runs it without -noreset, or a
  // loaded machine): try for up to 5 s before calling the display broken.
  static bool initGlfw() {
    for (int attempt = 0; attempt < 50; ++attempt) {
      if (glfwInit()) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    return false;
  }
  void SetUp() override {
    const char* display = std::getenv("DISPLAY");
    std::string why;
    if (!display || !*display) {
      why = "no DISPLAY (run through xvfb-run -a)";
    } else if (!initGlfw()) {
      const char* err = nullptr;
      glfwGetError(&err);
      why = std::string("glfwInit failed: ") + (err ? err : "?");
    } else {
      glfwInitialised_ = true;
      if (!glfwVulkanSupported()) why = "GLFW finds no Vulkan loader";
    }
    if (!why.empty()) {
      if (displayRequired()) FAIL() << why;
      GTEST_SKIP() << why;
    }
  }
  void TearDown() override {
    if (window_) glfwDestroyWindow(window_);
    if (glfwInitialised_) glfwTerminate();
  }

  GLFWwindow* openWindow(int width, int height) {
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
    window_ = glfwCreateWindow(width, height, "tsr::vk swapchain test", nullptr, nullptr);
    return window_;
  }

  // Polls events until the framebuffer has the size (X servers apply resizes asynchronously).
  bool waitForSize(int width, int height) {
    for (int i = 0; i < 200; ++i) {
      glfwPollEvents();
      int w = 0, h = 0;
      glfwGetFramebufferSize(window_, &w, &h);
      if (w == width && h == height) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return false;
  }

  void presentScenario(const std::shared_ptr<Device>& device);

  bool glfwInitialised_ = false;
  GLFWwindow* window_ = nullptr;
};

std::size_t litPixels(const std::vector<std::uint8_t>& bgra) {
  std::size_t n = 0;
  for (std::size_t i = 0; i + 3 < bgra.size(); i += 4)
    if (bgra[i] || bgra[i + 1] || bgra[i + 2]) ++n;
  return n;
}

void VulkanSwapchain::presentScenario(const std::shared_ptr<Device>& device) {
  ASSERT_NE(openWindow(96, 64), nullptr);
  ASSERT_TRUE(waitForSize(96, 64));

  Scene scene(device);
  Material red;
  red.baseColor = {0.9f, 0.1f, 0.1f};
  MaterialId redId = scene.addMaterial(red);
  MaterialId greyId = scene.addMaterial(Material{});
  scene.addInstance(scene.addMesh(test::groundQuad(0, 0, 3, -0.5f)), greyId, glm::mat4(1.0f));
  InstanceId ball = scene.addInstance(scene.addMesh(test::uvSphere(12, 16, 0.5f)), redId, glm::mat4(1.0f));
  scene.addLight(PointLight{{0, 2, 2}, glm::vec3(10.0f)});
  scene.setEnvironment(Environment::constant(glm::vec3(0.05f)));
  Renderer renderer(
      device,
      {.msaaSamples = 4, .shadows = false, .shadowMapSize = 256, .background = glm::vec4(0.1f, 0.2f, 0.4f, 1.0f)});
  const Camera cam96 = Camera::lookAt({0, 1.2f, 3}, {0, 0, 0}, {0, 1, 0}, 0.9f, 1.5f);

  {
    SwapchainTarget target(device, window_, {.readback = true});
    EXPECT_EQ(target.width(), 96u);
    EXPECT_EQ(target.height(), 64u);
    EXPECT_EQ(target.swapchainGeneration(), 1u);
    EXPECT_TRUE(target.format() == VK_FORMAT_B8G8R8A8_SRGB || target.format() == VK_FORMAT_B8G8R8A8_UNORM ||
                target.format() == VK_FORMAT_R8G8B8A8_SRGB || target.format() == VK_FORMAT_R8G8B8A8_UNORM);

    FrameBuffer fb(96, 64);
    for (int frame = 0; frame < 3; ++frame) {
      scene.setInstanceTransform(ball, glm::translate(glm::mat4(1.0f), {0.2f * float(frame) - 0.2f, 0, 0}));
      renderer.render(scene, cam96, Region::full(96, 64), fb);
      ASSERT_TRUE(target.present(fb)) << "frame " << frame;
      glfwPollEvents();
      ASSERT_EQ(target.lastPresentedWidth(), 96u);
      ASSERT_EQ(target.lastPresentedHeight(), 64u);
      const std::vector<std::uint8_t> expected = target.encode(fb);
      ASSERT_EQ(target.lastPresentedPixels().size(), expected.size());
      EXPECT_TRUE(target.lastPresentedPixels() == expected) << "frame " << frame;
      EXPECT_EQ(litPixels(target.lastPresentedPixels()), 96u * 64u);  // background is not black
    }
    EXPECT_EQ(target.framesPresented(), 3u);
    EXPECT_EQ(target.swapchainGeneration(), 1u);

    // Resize: the swapchain follows the window.
    glfwSetWindowSize(window_, 128, 80);
    ASSERT_TRUE(waitForSize(128, 80));
    const Camera cam128 = Camera::lookAt({0, 1.2f, 3}, {0, 0, 0}, {0, 1, 0}, 0.9f, 1.6f);
    FrameBuffer big(128, 80);
    renderer.render(scene, cam128, Region::full(128, 80), big);
    bool shown = target.present(big);
    if (!shown) shown = target.present(big);  // an out-of-date present is retried once by the caller
    ASSERT_TRUE(shown);
    EXPECT_GE(target.swapchainGeneration(), 2u);
    EXPECT_EQ(target.width(), 128u);
    EXPECT_EQ(target.height(), 80u);
    ASSERT_EQ(target.lastPresentedWidth(), 128u);
    ASSERT_EQ(target.lastPresentedHeight(), 80u);
    EXPECT_TRUE(target.lastPresentedPixels() == target.encode(big));

    // A smaller frame buffer lands top-left; the rest of the window is black.
    ASSERT_TRUE(target.present(fb));
    const std::vector<std::uint8_t>& got = target.lastPresentedPixels();
    const std::vector<std::uint8_t> small = target.encode(fb);
    std::size_t mismatches = 0;
    for (std::uint32_t y = 0; y < 80; ++y)
      for (std::uint32_t x = 0; x < 128; ++x)
        for (std::uint32_t c = 0; c < 4; ++c) {
          std::uint8_t want = (x < 96 && y < 64) ? small[(std::size_t(y) * 96 + x) * 4 + c] : (c == 3 ? 255 : 0);
          if (got[(std::size_t(y) * 128 + x) * 4 + c] != want) ++mismatches;
        }
    EXPECT_EQ(mismatches, 0u);
    EXPECT_EQ(target.framesPresented(), 5u);
  }
  EXPECT_EQ(glfwGetWindowAttrib(window_, GLFW_CLIENT_API), GLFW_NO_API);
  EXPECT_EQ(glfwGetError(nullptr), GLFW_NO_ERROR);
}

TEST_F(VulkanSwapchain, PresentsRenderedFramesAndFollowsResize) {
  std::shared_ptr<Device> device = Device::create(DeviceOptions::forWindows());
  ASSERT_TRUE(device->presentationEnabled());
  presentScenario(device);
}

TEST_F(VulkanSwapchain, PresentsWithoutValidationErrors) {
  if (!Device::validationLayerAvailable()) GTEST_SKIP() << "VK_LAYER_KHRONOS_validation not installed";
  std::shared_ptr<Device> device = Device::create(DeviceOptions::forWindows(/*validation=*/true));
  presentScenario(device);
  for (const std::string& m : device->validationMessages()) ADD_FAILURE() << m;
  EXPECT_EQ(device->validationErrors(), 0u);
  EXPECT_EQ(device->validationWarnings(), 0u);
}

TEST_F(VulkanSwapchain, RejectsDeviceWithoutWindowExtensions) {
  ASSERT_NE(openWindow(32, 32), nullptr);
  EXPECT_THROW(SwapchainTarget(test::device(), window_), Error);
}

}  // namespace
}  // namespace tsr::vk
