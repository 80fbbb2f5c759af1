#include "render_outputs.hpp"

#include <algorithm>

namespace tsr::med::embree_mediator {

namespace {
constexpr const char* kAlbedo = "albedo";
constexpr const char* kNormal = "normal";
constexpr const char* kDirect = "direct";
constexpr const char* kIndirect = "indirect";
constexpr const char* kVariance = "variance";
// Per pixel: samples traced for this view (r) and carried over from the
// views before by the history (g).
constexpr const char* kSamples = "samples";
}  // namespace

std::vector<std::string> accumulatedOutputNames() {
  return {kAlbedo, kNormal, kDirect, kIndirect, kVariance, kSamples};
}

FrameBuffer accumulatedFrame(const embree::FrameBuffer& fb, const RenderControl& control) {
  FrameBuffer full(fb.width(), fb.height());
  full.colour = fb.colourImage();
  full.depth = fb.depthImage();
  auto fill = [&](const char* name, auto read) {
    if (!control.wants(name)) return;
    auto& pixels = full.outputs[name];
    pixels.resize(full.colour.size());
    for (std::uint32_t y = 0; y < fb.height(); ++y)
      for (std::uint32_t x = 0; x < fb.width(); ++x) pixels[full.index(x, y)] = glm::vec4(read(x, y), 1.0f);
  };
  fill(kAlbedo, [&](std::uint32_t x, std::uint32_t y) { return fb.albedo(x, y); });
  fill(kNormal, [&](std::uint32_t x, std::uint32_t y) { return fb.normal(x, y); });
  fill(kDirect, [&](std::uint32_t x, std::uint32_t y) { return fb.mean(embree::Channel::Direct, x, y); });
  fill(kIndirect, [&](std::uint32_t x, std::uint32_t y) { return fb.mean(embree::Channel::Indirect, x, y); });
  fill(kVariance, [&](std::uint32_t x, std::uint32_t y) { return fb.variance(embree::Channel::Colour, x, y); });
  fill(kSamples, [&](std::uint32_t x, std::uint32_t y) {
    return glm::vec3(float(fb.tracedCount(x, y)), float(fb.inheritedCount(x, y)), 0.0f);
  });
  return full;
}

void writeWhittedFrame(const embree::WhittedImage& image, const RenderControl& control, FrameBuffer& full) {
  full.width = image.width();
  full.height = image.height();
  full.colour.assign(image.colour().begin(), image.colour().end());
  full.depth.assign(image.depth().begin(), image.depth().end());
  const std::vector<std::string> written = accumulatedOutputNames();
  std::erase_if(full.outputs, [&](const auto& output) {
    return !control.wants(output.first) || std::find(written.begin(), written.end(), output.first) == written.end();
  });
  auto fill = [&](const char* name, auto read) {
    if (!control.wants(name)) return;
    auto& pixels = full.outputs[name];
    pixels.resize(full.colour.size());
    for (std::size_t i = 0; i < pixels.size(); ++i) pixels[i] = glm::vec4(read(i), 1.0f);
  };
  fill(kAlbedo, [&](std::size_t i) { return image.albedo()[i]; });
  fill(kNormal, [&](std::size_t i) { return image.normal()[i]; });
  fill(kDirect, [&](std::size_t i) { return glm::vec3(image.colour()[i]); });
  fill(kIndirect, [](std::size_t) { return glm::vec3(0.0f); });
  fill(kVariance, [](std::size_t) { return glm::vec3(0.0f); });
  fill(kSamples, [&](std::size_t) { return glm::vec3(image.complete() ? 1.0f : 0.0f, 0.0f, 0.0f); });
}

}  // namespace tsr::med::embree_mediator
