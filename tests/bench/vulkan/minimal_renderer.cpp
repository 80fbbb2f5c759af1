#include "minimal_renderer.hpp"

#include "tsr/vk/error.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <cstring>
#include <span>

namespace tsr::vk::bench::spirv {
extern const std::span<const std::uint32_t> trivial_vert;
extern const std::span<const std::uint32_t> trivial_frag;
}  // namespace tsr::vk::bench::spirv

namespace tsr::vk::bench {

namespace {
template <class T>
T info(VkStructureType type) {
  T v{};
  v.sType = type;
  return v;
}

struct Allocation {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkImage image = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  void* mapped = nullptr;
};
}  // namespace

struct MinimalRenderer::Impl {
  std::shared_ptr<Device> device;
  VkDevice dev;
  std::uint32_t width, height;
  Allocation vertices, indices, instances, colourImage, depthImage, colourHost, depthHost;
  VkImageView colourView = VK_NULL_HANDLE, depthView = VK_NULL_HANDLE;
  VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VkPipeline pipeline = VK_NULL_HANDLE;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  VkDescriptorSet set = VK_NULL_HANDLE;
  VkCommandPool commandPool = VK_NULL_HANDLE;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  VkFence fence = VK_NULL_HANDLE;
  struct Draw {
    std::uint32_t firstIndex, indexCount;
    std::int32_t vertexOffset;
    std::uint32_t firstInstance, instanceCount;
  };
  std::vector<Draw> draws;
  glm::mat4 viewProj;

  std::uint32_t memoryType(std::uint32_t bits, VkMemoryPropertyFlags flags) { return device->memoryType(bits, flags); }

  Allocation buffer(VkDeviceSize size, VkBufferUsageFlags usage, VkMemoryPropertyFlags flags) {
    Allocation a;
    auto bci = info<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
    bci.size = size;
    bci.usage = usage;
    check(vkCreateBuffer(dev, &bci, nullptr, &a.buffer), "vkCreateBuffer");
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(dev, a.buffer, &req);
    auto mai = info<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
    mai.allocationSize = req.size;
    mai.memoryTypeIndex = memoryType(req.memoryTypeBits, flags);
    check(vkAllocateMemory(dev, &mai, nullptr, &a.memory), "vkAllocateMemory");
    check(vkBindBufferMemory(dev, a.buffer, a.memory, 0), "vkBindBufferMemory");
    if (flags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT)
      check(vkMapMemory(dev, a.memory, 0, VK_WHOLE_SIZE, 0, &a.mapped), "vkMapMemory");
    return a;
  }

  Allocation image(VkFormat format, VkImageUsageFlags usage, VkImageAspectFlags aspect, VkImageView& view) {
    Allocation a;
    auto ici = info<VkImageCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO);
    ici.imageType = VK_IMAGE_TYPE_2D;
    ici.format = format;
    ici.extent = {width, height, 1};
    ici.mipLevels = ici.arrayLayers = 1;
    ici.samples = VK_SAMPLE_COUNT_1_BIT;
    ici.usage = usage;
    check(vkCreateImage(dev, &ici, nullptr, &a.image), "vkCreateImage");
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(dev, a.image, &req);
    auto mai = info<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
    mai.allocationSize = req.size;
    mai.memoryTypeIndex = memoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    check(vkAllocateMemory(dev, &mai, nullptr, &a.memory), "vkAllocateMemory");
    check(vkBindImageMemory(dev, a.image, a.memory, 0), "vkBindImageMemory");
    auto vci = info<VkImageViewCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO);
    vci.image = a.image;
    vci.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vci.format = format;
    vci.subresourceRange = {aspect, 0, 1, 0, 1};
    check(vkCreateImageView(dev, &vci, nullptr, &view), "vkCreateImageView");
    return a;
  }

  void release(Allocation& a) {
    if (a.buffer) vkDestroyBuffer(dev, a.buffer, nullptr);
    if (a.image) vkDestroyImage(dev, a.image, nullptr);
    if (a.memory) vkFreeMemory(dev, a.memory, nullptr);
  }

  VkShaderModule module(std::span<const std::uint32_t> code) {
    auto ci = info<VkShaderModuleCreateInfo>(VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO);
    ci.codeSize = code.size_bytes();
    ci.pCode = code.data();
    VkShaderModule m;
    check(vkCreateShaderModule(dev, &ci, nullptr, &m), "vkCreateShaderModule");
    return m;
  }

  void createPipeline() {
    VkDescriptorSetLayoutBinding b{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_VERTEX_BIT, nullptr};
    auto slci = info<VkDescriptorSetLayoutCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO);
    slci.bindingCount = 1;
    slci.pBindings = &b;
    check(vkCreateDescriptorSetLayout(dev, &slci, nullptr, &setLayout), "vkCreateDescriptorSetLayout");
    VkPushConstantRange push{VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(glm::mat4)};
    auto plci = info<VkPipelineLayoutCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO);
    plci.setLayoutCount = 1;
    plci.pSetLayouts = &setLayout;
    plci.pushConstantRangeCount = 1;
    plci.pPushConstantRanges = &push;
    check(vkCreatePipelineLayout(dev, &plci, nullptr, &layout), "vkCreatePipelineLayout");

    VkShaderModule vs = module(spirv::trivial_vert), fs = module(spirv::trivial_frag);
    VkPipelineShaderStageCreateInfo stages[2] = {
        info<VkPipelineShaderStageCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO),
        info<VkPipelineShaderStageCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO)};
    stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
    stages[0].module = vs;
    stages[0].pName = "main";
    stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    stages[1].module = fs;
    stages[1].pName = "main";
    VkVertexInputBindingDescription binding{0, sizeof(glm::vec3), VK_VERTEX_INPUT_RATE_VERTEX};
    VkVertexInputAttributeDescription attribute{0, 0, VK_FORMAT_R32G32B32_SFLOAT, 0};
    auto vi = info<VkPipelineVertexInputStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO);
    vi.vertexBindingDescriptionCount = vi.vertexAttributeDescriptionCount = 1;
    vi.pVertexBindingDescriptions = &binding;
    vi.pVertexAttributeDescriptions = &attribute;
    auto ia = info<VkPipelineInputAssemblyStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO);
    ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkViewport viewport{0, 0, float(width), float(height), 0, 1};
    VkRect2D scissor{{0, 0}, {width, height}};
    auto vp = info<VkPipelineViewportStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO);
    vp.viewportCount = vp.scissorCount = 1;
    vp.pViewports = &viewport;
    vp.pScissors = &scissor;
    auto rs = info<VkPipelineRasterizationStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO);
    rs.cullMode = VK_CULL_MODE_NONE;  // the library draws two-sided too
    rs.lineWidth = 1.0f;
    auto ms = info<VkPipelineMultisampleStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO);
    ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    auto ds = info<VkPipelineDepthStencilStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO);
    ds.depthTestEnable = ds.depthWriteEnable = VK_TRUE;
    ds.depthCompareOp = VK_COMPARE_OP_LESS;
    VkPipelineColorBlendAttachmentState attachment{};
    attachment.colorWriteMask = 0xf;
    auto cb = info<VkPipelineColorBlendStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO);
    cb.attachmentCount = 1;
    cb.pAttachments = &attachment;
    VkFormat colourFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
    auto rendering = info<VkPipelineRenderingCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO);
    rendering.colorAttachmentCount = 1;
    rendering.pColorAttachmentFormats = &colourFormat;
    rendering.depthAttachmentFormat = VK_FORMAT_D32_SFLOAT;
    auto ci = info<VkGraphicsPipelineCreateInfo>(VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO);
    ci.pNext = &rendering;
    ci.stageCount = 2;
    ci.pStages = stages;
    ci.pVertexInputState = &vi;
    ci.pInputAssemblyState = &ia;
    ci.pViewportState = &vp;
    ci.pRasterizationState = &rs;
    ci.pMultisampleState = &ms;
    ci.pDepthStencilState = &ds;
    ci.pColorBlendState = &cb;
    ci.layout = layout;
    VkResult r = vkCreateGraphicsPipelines(dev, VK_NULL_HANDLE, 1, &ci, nullptr, &pipeline);
    vkDestroyShaderModule(dev, vs, nullptr);
    vkDestroyShaderModule(dev, fs, nullptr);
    check(r, "vkCreateGraphicsPipelines");
  }
};

MinimalRenderer::MinimalRenderer(std::shared_ptr<Device> device, const BenchScene& scene, std::uint32_t width,
                                 std::uint32_t height)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.device = std::move(device);
  m.dev = m.device->handle();
  m.width = width;
  m.height = height;

  // All meshes in one vertex and one index buffer, instances sorted by mesh.
  std::vector<glm::vec3> positions;
  std::vector<std::uint32_t> indices;
  std::vector<glm::mat4> models;
  for (std::uint32_t mesh = 0; mesh < scene.meshes.size(); ++mesh) {
    Impl::Draw d{std::uint32_t(indices.size()), std::uint32_t(scene.meshes[mesh].indices.size()),
                 std::int32_t(positions.size()), std::uint32_t(models.size()), 0};
    positions.insert(positions.end(), scene.meshes[mesh].positions.begin(), scene.meshes[mesh].positions.end());
    indices.insert(indices.end(), scene.meshes[mesh].indices.begin(), scene.meshes[mesh].indices.end());
    for (std::size_t i = 0; i < scene.instanceMesh.size(); ++i)
      if (scene.instanceMesh[i] == mesh) models.push_back(scene.instanceTransform[i]);
    d.instanceCount = std::uint32_t(models.size()) - d.firstInstance;
    m.draws.push_back(d);
  }
  const VkMemoryPropertyFlags host = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  // Host-visible geometry: on a GPU this would be staged, but upload cost is not what is measured.
  m.vertices = m.buffer(positions.size() * sizeof(glm::vec3), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, host);
  std::memcpy(m.vertices.mapped, positions.data(), positions.size() * sizeof(glm::vec3));
  m.indices = m.buffer(indices.size() * 4, VK_BUFFER_USAGE_INDEX_BUFFER_BIT, host);
  std::memcpy(m.indices.mapped, indices.data(), indices.size() * 4);
  m.instances = m.buffer(models.size() * sizeof(glm::mat4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, host);
  std::memcpy(m.instances.mapped, models.data(), models.size() * sizeof(glm::mat4));

  m.colourImage =
      m.image(VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
              VK_IMAGE_ASPECT_COLOR_BIT, m.colourView);
  m.depthImage =
      m.image(VK_FORMAT_D32_SFLOAT, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
              VK_IMAGE_ASPECT_DEPTH_BIT, m.depthView);
  const VkDeviceSize pixels = VkDeviceSize(width) * height;
  m.colourHost = m.buffer(pixels * 16, VK_BUFFER_USAGE_TRANSFER_DST_BIT, host | VK_MEMORY_PROPERTY_HOST_CACHED_BIT);
  m.depthHost = m.buffer(pixels * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, host | VK_MEMORY_PROPERTY_HOST_CACHED_BIT);

  m.createPipeline();
  VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1};
  auto dpci = info<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
  dpci.maxSets = 1;
  dpci.poolSizeCount = 1;
  dpci.pPoolSizes = &size;
  check(vkCreateDescriptorPool(m.dev, &dpci, nullptr, &m.pool), "vkCreateDescriptorPool");
  auto ai = info<VkDescriptorSetAllocateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO);
  ai.descriptorPool = m.pool;
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &m.setLayout;
  check(vkAllocateDescriptorSets(m.dev, &ai, &m.set), "vkAllocateDescriptorSets");
  VkDescriptorBufferInfo bi{m.instances.buffer, 0, VK_WHOLE_SIZE};
  auto w = info<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
  w.dstSet = m.set;
  w.descriptorCount = 1;
  w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  w.pBufferInfo = &bi;
  vkUpdateDescriptorSets(m.dev, 1, &w, 0, nullptr);

  auto cpci = info<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
  cpci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  cpci.queueFamilyIndex = m.device->queueFamily();
  check(vkCreateCommandPool(m.dev, &cpci, nullptr, &m.commandPool), "vkCreateCommandPool");
  auto cai = info<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
  cai.commandPool = m.commandPool;
  cai.commandBufferCount = 1;
  check(vkAllocateCommandBuffers(m.dev, &cai, &m.cmd), "vkAllocateCommandBuffers");
  auto fci = info<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
  check(vkCreateFence(m.dev, &fci, nullptr, &m.fence), "vkCreateFence");

  // Standard (not reversed) depth: the simplest thing.
  const Camera& c = scene.camera;
  glm::mat4 proj = glm::frustumRH_ZO(c.left, c.right, c.bottom, c.top, c.near, c.far);
  proj[1][1] *= -1.0f;
  proj[2][1] *= -1.0f;
  m.viewProj = proj * c.worldToCamera();
  colour_.resize(pixels);
  depth_.resize(pixels);
}

MinimalRenderer::~MinimalRenderer() {
  Impl& m = *impl_;
  vkDeviceWaitIdle(m.dev);
  vkDestroyFence(m.dev, m.fence, nullptr);
  vkDestroyCommandPool(m.dev, m.commandPool, nullptr);
  vkDestroyDescriptorPool(m.dev, m.pool, nullptr);
  vkDestroyPipeline(m.dev, m.pipeline, nullptr);
  vkDestroyPipelineLayout(m.dev, m.layout, nullptr);
  vkDestroyDescriptorSetLayout(m.dev, m.setLayout, nullptr);
  vkDestroyImageView(m.dev, m.colourView, nullptr);
  vkDestroyImageView(m.dev, m.depthView, nullptr);
  for (Allocation* a :
       {&m.vertices, &m.indices, &m.instances, &m.colourImage, &m.depthImage, &m.colourHost, &m.depthHost})
    m.release(*a);
}

void MinimalRenderer::renderFrame() {
  Impl& m = *impl_;
  VkCommandBuffer cmd = m.cmd;
  check(vkResetCommandBuffer(cmd, 0), "vkResetCommandBuffer");
  auto bi = info<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  check(vkBeginCommandBuffer(cmd, &bi), "vkBeginCommandBuffer");

  auto barrier = [&](VkImage image, VkImageAspectFlags aspect, VkImageLayout from, VkImageLayout to,
                     VkPipelineStageFlags src, VkAccessFlags srcAccess, VkPipelineStageFlags dst,
                     VkAccessFlags dstAccess) {
    auto b = info<VkImageMemoryBarrier>(VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER);
    b.srcAccessMask = srcAccess;
    b.dstAccessMask = dstAccess;
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = {aspect, 0, 1, 0, 1};
    vkCmdPipelineBarrier(cmd, src, dst, 0, 0, nullptr, 0, nullptr, 1, &b);
  };
  const VkPipelineStageFlags fragTests =
      VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  barrier(m.colourImage.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
          VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT, 0,
          VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT);
  barrier(m.depthImage.image, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
          VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, fragTests,
          VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT);

  auto ca = info<VkRenderingAttachmentInfo>(VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO);
  ca.imageView = m.colourView;
  ca.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  ca.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  ca.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  auto da = info<VkRenderingAttachmentInfo>(VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO);
  da.imageView = m.depthView;
  da.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
  da.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  da.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  da.clearValue.depthStencil = {1.0f, 0};
  auto ri = info<VkRenderingInfo>(VK_STRUCTURE_TYPE_RENDERING_INFO);
  ri.renderArea = {{0, 0}, {m.width, m.height}};
  ri.layerCount = 1;
  ri.colorAttachmentCount = 1;
  ri.pColorAttachments = &ca;
  ri.pDepthAttachment = &da;
  vkCmdBeginRendering(cmd, &ri);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, m.pipeline);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, m.layout, 0, 1, &m.set, 0, nullptr);
  vkCmdPushConstants(cmd, m.layout, VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(glm::mat4), &m.viewProj);
  VkDeviceSize offset = 0;
  vkCmdBindVertexBuffers(cmd, 0, 1, &m.vertices.buffer, &offset);
  vkCmdBindIndexBuffer(cmd, m.indices.buffer, 0, VK_INDEX_TYPE_UINT32);
  for (const Impl::Draw& d : m.draws)
    vkCmdDrawIndexed(cmd, d.indexCount, d.instanceCount, d.firstIndex, d.vertexOffset, d.firstInstance);
  vkCmdEndRendering(cmd);

  barrier(m.colourImage.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
          VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
          VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
  barrier(m.depthImage.image, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
          VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, fragTests, VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
          VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
  VkBufferImageCopy copy{};
  copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  copy.imageExtent = {m.width, m.height, 1};
  vkCmdCopyImageToBuffer(cmd, m.colourImage.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, m.colourHost.buffer, 1, &copy);
  copy.imageSubresource.aspectMask = VK_IMAGE_ASPECT_DEPTH_BIT;
  vkCmdCopyImageToBuffer(cmd, m.depthImage.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, m.depthHost.buffer, 1, &copy);
  auto toHost = info<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
  toHost.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  toHost.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &toHost, 0, nullptr, 0,
                       nullptr);
  check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
  auto si = info<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd;
  check(vkQueueSubmit(m.device->queue(), 1, &si, m.fence), "vkQueueSubmit");
  check(vkWaitForFences(m.dev, 1, &m.fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
  check(vkResetFences(m.dev, 1, &m.fence), "vkResetFences");
  std::memcpy(colour_.data(), m.colourHost.mapped, colour_.size() * sizeof(glm::vec4));
  std::memcpy(depth_.data(), m.depthHost.mapped, depth_.size() * sizeof(float));
}

}  // namespace tsr::vk::bench
