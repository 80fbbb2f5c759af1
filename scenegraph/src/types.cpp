#include "tsr/sg/types.hpp"

namespace tsr::sg {

std::string_view typeName(ContainerType t) {
  switch (t) {
    case ContainerType::Group:
      return "Group";
    case ContainerType::Transform:
      return "Transform";
    case ContainerType::Geometry:
      return "Geometry";
    case ContainerType::Image:
      return "Image";
    case ContainerType::SimpleMaterial:
      return "SimpleMaterial";
    case ContainerType::SurfaceMaterial:
      return "SurfaceMaterial";
    case ContainerType::Light:
      return "Light";
    case ContainerType::Camera:
      return "Camera";
    case ContainerType::Background:
      return "Background";
    case ContainerType::VolumeMaterial:
      return "VolumeMaterial";
  }
  return "Unknown";
}

}  // namespace tsr::sg
