#pragma once
// parsed::Scene to bytes and back, for the converted-scene cache
// (scene_cache.hpp). Little-endian, lengths before every array (its
// elements 8-byte aligned in the payload, zero padding between); decoding
// treats its input as hostile: every length is checked against what is
// left before anything is allocated, enums against their range, and the
// result is validated (parsed_scene_validation.hpp) before it is returned.
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "parsed_scene.hpp"

namespace tsr::sg::parsed {

std::vector<std::uint8_t> encodeScene(const Scene& scene);
// The same bytes handed to `sink` in order, in pieces: the 300 M-triangle
// plant's 12 GB are written to a file without a second copy in memory.
using ByteSink = std::function<void(std::span<const std::uint8_t>)>;
void encodeScene(const Scene& scene, const ByteSink& sink);
// Throws std::runtime_error naming what is wrong. With a `keeper` (of
// `bytes`' memory) the meshes' arrays are used in place (Primitive::held),
// else copied.
Scene decodeScene(std::span<const std::uint8_t> bytes, const std::shared_ptr<const void>& keeper = nullptr);

}  // namespace tsr::sg::parsed
