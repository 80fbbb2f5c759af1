#pragma once

#include <cstdint>
#include <span>

// Defined in the generated spirv.cpp (see cmake/embed_spirv.cmake).
namespace tsr::vk::spirv {
extern const std::span<const std::uint32_t> mesh_vert;
extern const std::span<const std::uint32_t> mesh_frag;
extern const std::span<const std::uint32_t> volume_vert;
extern const std::span<const std::uint32_t> volume_frag;
extern const std::span<const std::uint32_t> shadow_vert;
extern const std::span<const std::uint32_t> shadow_masked_vert;
extern const std::span<const std::uint32_t> shadow_masked_frag;
extern const std::span<const std::uint32_t> ids_vert;
extern const std::span<const std::uint32_t> ids_frag;
extern const std::span<const std::uint32_t> cull_comp;
extern const std::span<const std::uint32_t> depth_reduce_comp;
extern const std::span<const std::uint32_t> depth_reduce_ms_comp;
extern const std::span<const std::uint32_t> depth_downsample_comp;
}  // namespace tsr::vk::spirv
