#include "tsr/med/coverage/false_colour.hpp"

namespace tsr::med {

glm::vec3 falseColour(sg::ContainerId id) {
  if (id == sg::kNoContainer) return glm::vec3(0.0f);
  // splitmix64: consecutive ids get unrelated colours.
  std::uint64_t z = id + 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  z ^= z >> 31;
  auto channel = [&](int shift) { return 0.15f + 0.85f * static_cast<float>((z >> shift) & 0xff) / 255.0f; };
  return glm::vec3(channel(0), channel(8), channel(16));
}

}  // namespace tsr::med
