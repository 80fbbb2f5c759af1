#include "imgui_overlay.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>
#include <imgui.h>

namespace tsr::app {

namespace {

void check(VkResult result, const char* what) {
  if (result != VK_SUCCESS)
    throw std::runtime_error(std::string(what) + " failed (VkResult " + std::to_string(result) + ")");
}

void checkFromImGui(VkResult result) {
  if (result < 0) throw std::runtime_error("ImGui's Vulkan backend: VkResult " + std::to_string(result));
}

}  // namespace

ImGuiOverlay::ImGuiOverlay(std::shared_ptr<vk::Device> device, GLFWwindow* window) : device_(std::move(device)) {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini written into the user's folder
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForVulkan(window, true);

  // The pool sizes ImGui's own example uses; the font atlas takes one set.
  VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 16}};
  VkDescriptorPoolCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
  info.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  info.maxSets = 16;
  info.poolSizeCount = 1;
  info.pPoolSizes = sizes;
  check(vkCreateDescriptorPool(device_->handle(), &info, nullptr, &pool_), "vkCreateDescriptorPool");
}

ImGuiOverlay::~ImGuiOverlay() {
  vkDeviceWaitIdle(device_->handle());
  destroyFramebuffers();
  if (rendererReady_) ImGui_ImplVulkan_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  if (renderPass_) vkDestroyRenderPass(device_->handle(), renderPass_, nullptr);
  vkDestroyDescriptorPool(device_->handle(), pool_, nullptr);
}

void ImGuiOverlay::beginFrame() {
  if (rendererReady_) ImGui_ImplVulkan_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  frameReady_ = false;
}

void ImGuiOverlay::endFrame() {
  ImGui::Render();
  frameReady_ = true;
}

// The render pass keeps what the target copied in (LOAD) and hands the image
// back in TRANSFER_DST_OPTIMAL, the layout the target expects.
void ImGuiOverlay::initialiseRenderer(VkFormat format, std::uint32_t imageCount) {
  VkDevice dev = device_->handle();
  VkAttachmentDescription colour{};
  colour.format = format;
  colour.samples = VK_SAMPLE_COUNT_1_BIT;
  colour.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
  colour.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  colour.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  colour.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  colour.initialLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  colour.finalLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &ref;
  VkSubpassDependency deps[2]{};
  deps[0].srcSubpass = VK_SUBPASS_EXTERNAL;
  deps[0].dstSubpass = 0;
  deps[0].srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
  deps[0].srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  deps[0].dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  deps[0].dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  deps[1].srcSubpass = 0;
  deps[1].dstSubpass = VK_SUBPASS_EXTERNAL;
  deps[1].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  deps[1].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  deps[1].dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
  deps[1].dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
  VkRenderPassCreateInfo rp{};
  rp.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO;
  rp.attachmentCount = 1;
  rp.pAttachments = &colour;
  rp.subpassCount = 1;
  rp.pSubpasses = &subpass;
  rp.dependencyCount = 2;
  rp.pDependencies = deps;
  check(vkCreateRenderPass(dev, &rp, nullptr, &renderPass_), "vkCreateRenderPass");

  ImGui_ImplVulkan_InitInfo init{};
  init.Instance = device_->instance();
  init.PhysicalDevice = device_->physicalDevice();
  init.Device = dev;
  init.QueueFamily = device_->queueFamily();
  init.Queue = device_->queue();
  init.DescriptorPool = pool_;
  init.MinImageCount = std::max<std::uint32_t>(imageCount, 2);
  init.ImageCount = std::max<std::uint32_t>(imageCount, 2);
  init.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
  init.CheckVkResultFn = checkFromImGui;
  if (!ImGui_ImplVulkan_Init(&init, renderPass_)) throw std::runtime_error("ImGui_ImplVulkan_Init failed");
  device_->submitAndWait([](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
  ImGui_ImplVulkan_DestroyFontUploadObjects();
  rendererReady_ = true;
  format_ = format;
  // ImGui's colours are sRGB values; an sRGB swapchain image encodes what the
  // shader writes, so the style's colours are decoded once to look as meant.
  if (format == VK_FORMAT_B8G8R8A8_SRGB || format == VK_FORMAT_R8G8B8A8_SRGB) {
    ImGuiStyle& style = ImGui::GetStyle();
    for (ImVec4& c : style.Colors) {
      c.x = std::pow(c.x, 2.2f);
      c.y = std::pow(c.y, 2.2f);
      c.z = std::pow(c.z, 2.2f);
    }
  }
}

void ImGuiOverlay::destroyFramebuffers() {
  VkDevice dev = device_->handle();
  for (VkFramebuffer f : framebuffers_) vkDestroyFramebuffer(dev, f, nullptr);
  for (VkImageView v : views_) vkDestroyImageView(dev, v, nullptr);
  framebuffers_.clear();
  views_.clear();
}

void ImGuiOverlay::swapchainChanged(VkFormat format, VkExtent2D extent, const std::vector<VkImage>& images) {
  destroyFramebuffers();
  extent_ = extent;
  if (images.empty()) return;
  if (!rendererReady_) initialiseRenderer(format, std::uint32_t(images.size()));
  if (format != format_) throw std::runtime_error("ImGuiOverlay: the swapchain changed its format");
  VkDevice dev = device_->handle();
  for (VkImage image : images) {
    VkImageViewCreateInfo vi{};
    vi.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
    vi.image = image;
    vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vi.format = format;
    vi.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkImageView view = VK_NULL_HANDLE;
    check(vkCreateImageView(dev, &vi, nullptr, &view), "vkCreateImageView");
    views_.push_back(view);
    VkFramebufferCreateInfo fi{};
    fi.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO;
    fi.renderPass = renderPass_;
    fi.attachmentCount = 1;
    fi.pAttachments = &view;
    fi.width = extent.width;
    fi.height = extent.height;
    fi.layers = 1;
    VkFramebuffer framebuffer = VK_NULL_HANDLE;
    check(vkCreateFramebuffer(dev, &fi, nullptr, &framebuffer), "vkCreateFramebuffer");
    framebuffers_.push_back(framebuffer);
  }
  ImGui_ImplVulkan_SetMinImageCount(std::max<std::uint32_t>(std::uint32_t(images.size()), 2));
}

void ImGuiOverlay::record(VkCommandBuffer cmd, std::uint32_t index) {
  ImDrawData* data = ImGui::GetDrawData();
  if (!frameReady_ || !data || index >= framebuffers_.size()) return;
  VkRenderPassBeginInfo begin{};
  begin.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
  begin.renderPass = renderPass_;
  begin.framebuffer = framebuffers_[index];
  begin.renderArea.extent = extent_;
  vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
  ImGui_ImplVulkan_RenderDrawData(data, cmd);
  vkCmdEndRenderPass(cmd);
}

}  // namespace tsr::app
