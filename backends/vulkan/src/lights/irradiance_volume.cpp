// Renderer::setIrradianceVolume: the volume's upload (probe_volume.glsl reads it).
#include "renderer_impl.hpp"

#include <cstring>

namespace tsr::vk {

void Renderer::setIrradianceVolume(std::shared_ptr<const backend::IrradianceVolume> volume) {
  using backend::IrradianceVolume;
  Impl& r = *impl_;
  if (!volume || volume->empty()) {
    if (r.irradianceVolume) ++r.irradianceVersion;
    r.irradianceVolume.reset();
    return;
  }
  if (volume == r.irradianceVolume) return;  // held volumes are immutable
  const std::size_t probes = volume->probeCount();
  if (volume->irradiance.size() != probes * IrradianceVolume::kFaces ||
      volume->distance.size() != probes * IrradianceVolume::kDistanceTexels)
    throw Error("irradiance volume of " + std::to_string(probes) + " probes holds " +
                std::to_string(volume->irradiance.size()) + " faces and " + std::to_string(volume->distance.size()) +
                " distance texels");
  const VkDeviceSize irradianceBytes = volume->irradiance.size() * sizeof(glm::vec4);
  const VkDeviceSize bytes = irradianceBytes + volume->distance.size() * sizeof(glm::vec2);
  ensureHost(r.device, r.irradianceBuffer, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  auto* into = static_cast<unsigned char*>(r.irradianceBuffer.mapped());
  std::memcpy(into, volume->irradiance.data(), irradianceBytes);
  std::memcpy(into + irradianceBytes, volume->distance.data(), bytes - irradianceBytes);
  r.irradianceVolume = std::move(volume);
  ++r.irradianceVersion;
}

}  // namespace tsr::vk
