#include "tsr/med/vulkan/register.hpp"

#include "vulkan_viewport.hpp"

namespace tsr::med {

void registerVulkan(ViewportRegistry& registry) {
  registry.add("vulkan", vulkan_mediator::vulkanCapabilities(),
               [&registry](ViewportSettings settings, ContextPool& contexts) -> std::unique_ptr<Viewport> {
                 std::string key =
                     "vulkan:" + std::to_string(settings.root) + ":" + std::to_string(settings.background);
                 sg::ContainerId root = settings.root, background = settings.background;
                 auto context = contexts.acquire<vulkan_mediator::VulkanContext>(key, [&] {
                   return std::make_shared<vulkan_mediator::VulkanContext>(vk::sharedDevice(), root, background);
                 });
                 // Made now, converted and traced only when a frame reads it.
                 auto bounced = registry.bouncedLight(root, background, contexts);
                 return std::make_unique<vulkan_mediator::VulkanViewport>(std::move(settings), std::move(context),
                                                                          std::move(bounced));
               });
}

}  // namespace tsr::med
