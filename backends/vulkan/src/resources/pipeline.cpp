#include "resources/pipeline.hpp"

#include "tsr/vk/error.hpp"
#include "vk_struct.hpp"

#include <cstdint>
#include <utility>
#include <vector>

namespace tsr::vk {

namespace {
VkShaderModule createModule(VkDevice device, std::span<const std::uint32_t> code) {
  VkShaderModuleCreateInfo ci = vkStruct<VkShaderModuleCreateInfo>(VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO);
  ci.codeSize = code.size_bytes();
  ci.pCode = code.data();
  VkShaderModule m = VK_NULL_HANDLE;
  check(vkCreateShaderModule(device, &ci, nullptr, &m), "vkCreateShaderModule");
  return m;
}

// Filled triangles, culled as asked, with depth bias when asked.
VkPipelineRasterizationStateCreateInfo rasterization(const PipelineDesc& d) {
  VkPipelineRasterizationStateCreateInfo rs =
      vkStruct<VkPipelineRasterizationStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO);
  rs.polygonMode = VK_POLYGON_MODE_FILL;
  rs.cullMode = d.cull;
  // The projection flips y, so counter-clockwise in the image (as the viewer
  // sees it) stays counter-clockwise in framebuffer terms.
  rs.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  rs.depthBiasEnable = d.depthBias ? VK_TRUE : VK_FALSE;
  rs.lineWidth = 1.0f;
  return rs;
}

VkPipelineMultisampleStateCreateInfo multisample(const PipelineDesc& d) {
  VkPipelineMultisampleStateCreateInfo ms =
      vkStruct<VkPipelineMultisampleStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO);
  ms.rasterizationSamples = d.samples;
  return ms;
}

// Depth always tested; written and compared as asked.
VkPipelineDepthStencilStateCreateInfo depthStencil(const PipelineDesc& d) {
  VkPipelineDepthStencilStateCreateInfo ds =
      vkStruct<VkPipelineDepthStencilStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO);
  ds.depthTestEnable = VK_TRUE;
  ds.depthWriteEnable = d.depthWrite ? VK_TRUE : VK_FALSE;
  ds.depthCompareOp = d.depthCompare;
  return ds;
}

// All four channels written; alpha blending, or dual-source blending (the
// shader's second output weighs the destination). Both add
// source x srcColour + destination x dstColour, and for alpha
// source + destination x dstAlpha.
VkPipelineColorBlendAttachmentState colourBlend(const PipelineDesc& d) {
  VkPipelineColorBlendAttachmentState attachment{};
  attachment.colorWriteMask =
      VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
  const auto blend = [&](VkBlendFactor srcColour, VkBlendFactor dstColour, VkBlendFactor dstAlpha) {
    attachment.blendEnable = VK_TRUE;
    attachment.srcColorBlendFactor = srcColour;
    attachment.dstColorBlendFactor = dstColour;
    attachment.colorBlendOp = VK_BLEND_OP_ADD;
    attachment.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
    attachment.dstAlphaBlendFactor = dstAlpha;
    attachment.alphaBlendOp = VK_BLEND_OP_ADD;
  };
  if (d.blend)
    blend(VK_BLEND_FACTOR_SRC_ALPHA, VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA, VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA);
  if (d.dualSourceBlend) blend(VK_BLEND_FACTOR_ONE, VK_BLEND_FACTOR_SRC1_COLOR, VK_BLEND_FACTOR_SRC1_ALPHA);
  return attachment;
}

}  // namespace

// The shaders, their specialization and the vertex streams here; the
// fixed-function state from the named parts above.
Pipeline::Pipeline(const Device& device, const PipelineDesc& d) : device_(device.handle()) {
  VkShaderModule vert = createModule(device_, d.vertexSpirv);
  VkShaderModule frag = d.fragmentSpirv.empty() ? VK_NULL_HANDLE : createModule(device_, d.fragmentSpirv);
  struct Modules {
    VkDevice device;
    VkShaderModule a, b;
    ~Modules() {
      vkDestroyShaderModule(device, a, nullptr);
      if (b) vkDestroyShaderModule(device, b, nullptr);
    }
  } modules{device_, vert, frag};

  VkPipelineShaderStageCreateInfo stages[2]{};
  stages[0] = vkStruct<VkPipelineShaderStageCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO);
  stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
  stages[0].module = vert;
  stages[0].pName = "main";
  stages[1] = vkStruct<VkPipelineShaderStageCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO);
  stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
  stages[1].module = frag;
  stages[1].pName = "main";
  std::vector<VkSpecializationMapEntry> entries;
  for (std::uint32_t i = 0; i < d.fragmentConstants.size(); ++i)
    entries.push_back({i, i * std::uint32_t(sizeof(std::uint32_t)), sizeof(std::uint32_t)});
  VkSpecializationInfo specialization{std::uint32_t(entries.size()), entries.data(),
                                      d.fragmentConstants.size() * sizeof(std::uint32_t), d.fragmentConstants.data()};
  if (!entries.empty()) stages[1].pSpecializationInfo = &specialization;

  // Separate streams, so a vertex range edit touches one contiguous range per
  // attribute; all three compact (src/scene/vertex_encoding.hpp).
  const VkVertexInputBindingDescription allBindings[3] = {
      {0, device.positionBytes(), VK_VERTEX_INPUT_RATE_VERTEX},
      {1, 2 * sizeof(std::int16_t), VK_VERTEX_INPUT_RATE_VERTEX},
      {2, 2 * sizeof(std::uint16_t), VK_VERTEX_INPUT_RATE_VERTEX},
  };
  const VkVertexInputAttributeDescription allAttributes[3] = {
      {0, 0, device.positionFormat(), 0},
      {1, 1, VK_FORMAT_R16G16_SNORM, 0},
      {2, 2, VK_FORMAT_R16G16_UNORM, 0},
  };
  VkPipelineVertexInputStateCreateInfo vi =
      vkStruct<VkPipelineVertexInputStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO);
  vi.vertexBindingDescriptionCount = d.vertexStreams;
  vi.pVertexBindingDescriptions = allBindings;
  // Without normals the uv attribute moves up: its binding stays 2.
  const VkVertexInputAttributeDescription positionAndUv[2] = {allAttributes[0], allAttributes[2]};
  const bool skipNormals = !d.normals && d.vertexStreams == 3;
  vi.vertexAttributeDescriptionCount = skipNormals ? 2 : d.vertexStreams;
  vi.pVertexAttributeDescriptions = skipNormals ? positionAndUv : allAttributes;

  VkPipelineInputAssemblyStateCreateInfo ia =
      vkStruct<VkPipelineInputAssemblyStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO);
  ia.topology = d.topology;

  VkPipelineViewportStateCreateInfo vp =
      vkStruct<VkPipelineViewportStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO);
  vp.viewportCount = 1;
  vp.scissorCount = 1;

  const VkPipelineRasterizationStateCreateInfo rs = rasterization(d);
  const VkPipelineMultisampleStateCreateInfo ms = multisample(d);
  const VkPipelineDepthStencilStateCreateInfo ds = depthStencil(d);
  const VkPipelineColorBlendAttachmentState attachment = colourBlend(d);
  const bool hasColour = d.colourFormat != VK_FORMAT_UNDEFINED;
  VkPipelineColorBlendStateCreateInfo cb =
      vkStruct<VkPipelineColorBlendStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO);
  cb.attachmentCount = hasColour ? 1 : 0;
  cb.pAttachments = &attachment;

  std::vector<VkDynamicState> dynamic = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  if (d.depthBias) dynamic.push_back(VK_DYNAMIC_STATE_DEPTH_BIAS);
  VkPipelineDynamicStateCreateInfo dyn =
      vkStruct<VkPipelineDynamicStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO);
  dyn.dynamicStateCount = std::uint32_t(dynamic.size());
  dyn.pDynamicStates = dynamic.data();

  VkPipelineRenderingCreateInfo rendering =
      vkStruct<VkPipelineRenderingCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO);
  rendering.colorAttachmentCount = hasColour ? 1 : 0;
  rendering.pColorAttachmentFormats = &d.colourFormat;
  rendering.depthAttachmentFormat = d.depthFormat;

  VkGraphicsPipelineCreateInfo ci =
      vkStruct<VkGraphicsPipelineCreateInfo>(VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO);
  ci.pNext = &rendering;
  ci.stageCount = frag ? 2 : 1;
  ci.pStages = stages;
  ci.pVertexInputState = &vi;
  ci.pInputAssemblyState = &ia;
  ci.pViewportState = &vp;
  ci.pRasterizationState = &rs;
  ci.pMultisampleState = &ms;
  ci.pDepthStencilState = &ds;
  ci.pColorBlendState = &cb;
  ci.pDynamicState = &dyn;
  ci.layout = d.layout;
  check(vkCreateGraphicsPipelines(device_, VK_NULL_HANDLE, 1, &ci, nullptr, &pipeline_), "vkCreateGraphicsPipelines");
}

Pipeline::~Pipeline() {
  if (pipeline_) vkDestroyPipeline(device_, pipeline_, nullptr);
}

Pipeline::Pipeline(Pipeline&& o) noexcept : device_(o.device_), pipeline_(std::exchange(o.pipeline_, VK_NULL_HANDLE)) {}

Pipeline& Pipeline::operator=(Pipeline&& o) noexcept {
  if (this != &o) {
    if (pipeline_) vkDestroyPipeline(device_, pipeline_, nullptr);
    device_ = o.device_;
    pipeline_ = std::exchange(o.pipeline_, VK_NULL_HANDLE);
  }
  return *this;
}

}  // namespace tsr::vk
