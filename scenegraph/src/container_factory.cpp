#include "tsr/sg/container_factory.hpp"

#include <array>
#include <stdexcept>

#include "tsr/sg/container_types.hpp"

namespace tsr::sg {

namespace {
template <class... T>
std::unique_ptr<Container> makeOneOf(ContainerType type, std::tuple<T...>*) {
  std::unique_ptr<Container> made;
  ((type == T::kType ? void(made = std::make_unique<T>()) : void()), ...);
  return made;
}
}  // namespace

std::unique_ptr<Container> makeContainer(ContainerType type) {
  if (auto made = makeOneOf(type, static_cast<ContainerTypes*>(nullptr))) return made;
  throw std::invalid_argument("unknown container type " + std::to_string(static_cast<unsigned>(type)));
}

const Container& prototype(ContainerType type) {
  static const auto prototypes = [] {
    std::array<std::unique_ptr<Container>, kContainerTypeCount + 1> all;
    for (unsigned t = 1; t <= kContainerTypeCount; ++t) all[t] = makeContainer(static_cast<ContainerType>(t));
    return all;
  }();
  return *prototypes.at(static_cast<unsigned>(type));
}

}  // namespace tsr::sg
