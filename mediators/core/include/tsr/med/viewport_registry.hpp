#pragma once
// Creates viewports by back-end name, so that the cluster layer and apps
// never include a back-end header. Each back-end's mediator library offers
// a registerXxx(ViewportRegistry&) function; executables call those.
#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "tsr/med/bounced_light.hpp"
#include "tsr/med/context_pool.hpp"
#include "tsr/med/viewport.hpp"

namespace tsr::med {

class UnknownBackend : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// Not copied or moved: factories may refer to the registry they are in
// (the rasterizer's asks it for bounced light).
class ViewportRegistry {
 public:
  ViewportRegistry() = default;
  ViewportRegistry(const ViewportRegistry&) = delete;
  ViewportRegistry& operator=(const ViewportRegistry&) = delete;

  using Factory = std::function<std::unique_ptr<Viewport>(ViewportSettings, ContextPool&)>;

  // `capabilities` must outlive the registry (a back-end's static table).
  void add(const std::string& backend, const BackendCapabilities& capabilities, Factory factory);
  // Throws UnknownBackend naming the back-ends it knows, and UnknownParameter
  // or BadParameterValue for parameters the back-end does not take.
  std::unique_ptr<Viewport> create(ViewportSettings settings, ContextPool& contexts) const;
  // Throws UnknownBackend.
  const BackendCapabilities& capabilities(const std::string& backend) const;
  std::vector<std::string> backends() const;
  // The parameters of `offered` that `backend` declares: options meant for
  // every viewport of a window (spp, threads) reach the back-ends that take them.
  Parameters parametersFor(const std::string& backend, const Parameters& offered) const;
  // Throws UnknownParameter for a parameter none of `backends` declares
  // (BadParameterValue for a bad value of one that does), naming what they take.
  void requireDeclared(const Parameters& given, const std::vector<std::string>& backends) const;
  bool has(const std::string& backend) const { return entries_.count(backend) != 0; }

  // Bounced light (bounced_light.hpp) for viewports of back-ends that do
  // not trace it: offered by a back-end that does, made once per root and
  // background in `contexts`.
  using BouncedLightFactory =
      std::function<std::shared_ptr<BouncedLight>(sg::ContainerId root, sg::ContainerId background, ContextPool&)>;
  void addBouncedLight(const std::string& backend, BouncedLightFactory factory);
  // The bounced light of the first back-end (by name) that offers one; null
  // when none does (a build without a ray tracer).
  std::shared_ptr<BouncedLight> bouncedLight(sg::ContainerId root, sg::ContainerId background,
                                             ContextPool& contexts) const;

 private:
  struct Entry {
    const BackendCapabilities* capabilities;
    Factory factory;
  };
  const Entry& entry(const std::string& backend) const;

  std::map<std::string, Entry> entries_;
  std::map<std::string, BouncedLightFactory> bouncedLights_;
};

}  // namespace tsr::med
