#pragma once
// GLFW started for a program's Vulkan windows, or an error a person can act
// on: what GLFW says, and `withoutDisplay` (what to do when there is no
// display). Once it returns, the caller ends GLFW (glfwTerminate) when its
// windows are gone.
#include <stdexcept>
#include <string>

#define GLFW_INCLUDE_VULKAN  // as every window of ours: Vulkan surfaces
#include <GLFW/glfw3.h>

namespace tsr::app {

inline void startGlfw(const std::string& withoutDisplay) {
  if (!glfwInit()) {
    const char* why = nullptr;
    glfwGetError(&why);
    throw std::runtime_error(std::string("cannot open a window: ") + (why ? why : "glfwInit failed") + " (" +
                             withoutDisplay + ")");
  }
  if (!glfwVulkanSupported()) {
    glfwTerminate();
    throw std::runtime_error("cannot open a window: GLFW finds no Vulkan loader");
  }
}

}  // namespace tsr::app
