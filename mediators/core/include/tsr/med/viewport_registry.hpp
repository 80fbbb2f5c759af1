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

#include "tsr/med/context_pool.hpp"
#include "tsr/med/viewport.hpp"

namespace tsr::med {

class UnknownBackend : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

class ViewportRegistry {
 public:
  using Factory = std::function<std::unique_ptr<Viewport>(ViewportSettings, ContextPool&)>;

  void add(const std::string& backend, Factory factory);
  // Throws UnknownBackend naming the back-ends it knows.
  std::unique_ptr<Viewport> create(ViewportSettings settings, ContextPool& contexts) const;
  std::vector<std::string> backends() const;
  bool has(const std::string& backend) const { return factories_.count(backend) != 0; }

 private:
  std::map<std::string, Factory> factories_;
};

}  // namespace tsr::med
