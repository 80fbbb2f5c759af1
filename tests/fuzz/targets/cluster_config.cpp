#include <string>

#include "fuzz_targets.hpp"
#include "tsr/cluster/cluster_config.hpp"

namespace tsr::fuzz {

void clusterConfig(Bytes bytes) {
  const std::string text(bytes.begin(), bytes.end());
  try {
    cluster::parseClusterConfig(text, "fuzz-input").validate();
  } catch (const cluster::ConfigError&) {}
}

}  // namespace tsr::fuzz
