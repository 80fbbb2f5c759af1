#include "tsr/sg/container_factory.hpp"

#include <array>
#include <stdexcept>

#include "tsr/sg/scene.hpp"

namespace tsr::sg {

std::unique_ptr<Container> makeContainer(ContainerType type) {
  switch (type) {
    case ContainerType::Group:
      return std::make_unique<Group>();
    case ContainerType::Transform:
      return std::make_unique<Transform>();
    case ContainerType::Geometry:
      return std::make_unique<Geometry>();
    case ContainerType::Image:
      return std::make_unique<Image>();
    case ContainerType::SimpleMaterial:
      return std::make_unique<SimpleMaterial>();
    case ContainerType::SurfaceMaterial:
      return std::make_unique<SurfaceMaterial>();
    case ContainerType::Light:
      return std::make_unique<Light>();
    case ContainerType::Camera:
      return std::make_unique<Camera>();
    case ContainerType::Background:
      return std::make_unique<Background>();
  }
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
