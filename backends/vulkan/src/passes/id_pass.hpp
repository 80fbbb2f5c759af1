#pragma once

#include "resources/buffer.hpp"
#include "resources/command_slot.hpp"
#include "resources/image.hpp"
#include "resources/pipeline.hpp"

#include "tsr/vk/id_buffer.hpp"
#include "tsr/vk/vocabulary.hpp"

#include <optional>

namespace tsr::vk {

struct SceneState;

// The id pass: opaque instances drawn with positions only into an R32_UINT
// attachment holding each instance's object id, one sample per pixel (at
// its centre, like a ray through it), plus depth; both read back. Owns its
// descriptor layout, pipeline and targets, so the colour pass is untouched.
class IdPass {
 public:
  explicit IdPass(const Device& device);
  ~IdPass();
  IdPass(const IdPass&) = delete;
  IdPass& operator=(const IdPass&) = delete;

  // Returns the number of instanced draws recorded.
  std::uint32_t render(SceneState& scene, const Camera& camera, const Region& region, IdBuffer& out);

 private:
  struct Target {
    std::uint32_t width = 0, height = 0;
    Image ids, depth;
    Buffer idReadback, depthReadback;
  };

  const Device& device_;
  VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  std::optional<DescriptorSlot> descriptors_;  // made once the layout exists
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  std::optional<CommandSlot> commands_;
  Pipeline pipeline_;
  Pipeline linePipeline_, pointPipeline_;  // the same, for lines and points
  Buffer frame_;                           // viewProj
  Buffer drawOrder_;                       // opaque instance slots, in draw-group order
  std::optional<Target> target_;
};

}  // namespace tsr::vk
