#include "tsr/med/coverage/ranking.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace tsr::med {

namespace {
constexpr std::uint64_t kLow = std::uint64_t{1} << 24;

bool isCount(float v, std::uint64_t limit) { return v >= 0.0f && v < float(limit) && std::floor(v) == v; }

const std::vector<glm::vec4>& idOutput(const FrameBuffer& image) {
  auto it = image.outputs.find(kIdOutput);
  if (it == image.outputs.end())
    throw std::invalid_argument("the frame buffer has no 'id' output (render with the coverage back-end)");
  if (it->second.size() != std::size_t{image.width} * image.height)
    throw std::invalid_argument("the frame buffer's 'id' output does not match its size");
  return it->second;
}

std::string nameOf(const sg::Scene& scene, sg::ContainerId id) {
  const sg::Container* c = scene.find(id);
  if (!c) return {};
  if (!c->name().empty() || c->type() != sg::ContainerType::Transform) return c->name();
  for (sg::ContainerId child : static_cast<const sg::Transform*>(c)->children())
    if (const auto* g = scene.find<sg::Geometry>(child); g && !g->name().empty()) return g->name();
  return {};
}
}  // namespace

glm::vec4 encodeObjectId(sg::ContainerId id) {
  if (id == sg::kNoContainer) return glm::vec4(0.0f);
  if (id >= kLow * kLow) throw std::invalid_argument("object id " + std::to_string(id) + " does not fit the id output");
  return glm::vec4(float(id % kLow), float(id / kLow), 0.0f, 1.0f);
}

sg::ContainerId decodeObjectId(const glm::vec4& v) {
  if (!isCount(v.r, kLow) || !isCount(v.g, kLow))
    throw std::invalid_argument("id output value (" + std::to_string(v.r) + ", " + std::to_string(v.g) +
                                ") is not an id");
  return static_cast<sg::ContainerId>(v.g) * kLow + static_cast<sg::ContainerId>(v.r);
}

std::vector<RankedObject> rankObjects(const FrameBuffer& image, const sg::Scene& scene) {
  const auto& ids = idOutput(image);
  std::unordered_map<sg::ContainerId, std::uint64_t> count;
  for (std::size_t i = 0; i < ids.size();) {
    // Count runs of equal values: neighbours mostly show the same object.
    std::size_t end = i + 1;
    while (end < ids.size() && ids[end].r == ids[i].r && ids[end].g == ids[i].g) ++end;
    if (sg::ContainerId id = decodeObjectId(ids[i]); id != sg::kNoContainer) count[id] += end - i;
    i = end;
  }
  std::vector<RankedObject> ranked;
  ranked.reserve(count.size());
  const double all = static_cast<double>(ids.size());
  for (const auto& [id, n] : count) ranked.push_back({id, nameOf(scene, id), n, static_cast<double>(n) / all});
  std::sort(ranked.begin(), ranked.end(), [](const RankedObject& a, const RankedObject& b) {
    return a.pixels != b.pixels ? a.pixels > b.pixels : a.id < b.id;
  });
  return ranked;
}

std::uint64_t backgroundPixels(const FrameBuffer& image) {
  const auto& ids = idOutput(image);
  return static_cast<std::uint64_t>(
      std::count_if(ids.begin(), ids.end(), [](const glm::vec4& v) { return decodeObjectId(v) == sg::kNoContainer; }));
}

sg::ContainerId objectOf(const sg::Scene& scene, const FlatNode& instance) {
  for (auto it = instance.path.rbegin(); it != instance.path.rend(); ++it)
    if (scene.find<sg::Transform>(*it)) return *it;
  return instance.id;
}

}  // namespace tsr::med
