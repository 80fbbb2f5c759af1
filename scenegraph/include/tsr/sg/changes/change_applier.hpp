#pragma once
// Applies one change list to a replica in two passes: first every check that
// could fail (version, ids, types, array lengths, references, cycles), then
// the mutation, which cannot fail. So a list that does not fit leaves the
// replica exactly as it was.
#include <unordered_map>
#include <unordered_set>

#include "tsr/sg/scene.hpp"

namespace tsr::sg {

class ChangeApplier {
 public:
  ChangeApplier(Scene& scene, const ChangeList& list) : scene_(scene), list_(list) {}
  void run();

 private:
  void validate();
  void checkIds();
  void checkReferences();
  void checkNoCycles() const;
  void mutate();
  void read(Container& c, const ChangeEntry& e, bool creation);
  [[noreturn]] void fail(const std::string& reason) const;

  Scene& scene_;
  const ChangeList& list_;
  std::unordered_map<ContainerId, ContainerType> created_;
  std::unordered_map<ContainerId, const ChangeEntry*> changed_;
  std::unordered_set<ContainerId> destroyed_;
};

}  // namespace tsr::sg
