#include "tsr/sg/types.hpp"

#include <array>

namespace tsr::sg {

std::string_view typeName(ContainerType t) {
  // Indexed by the wire number (1-based); kContainerTypeCount is kept with the enum.
  static constexpr std::array<std::string_view, kContainerTypeCount + 1> kNames{
      "Unknown",         "Group", "Transform", "Geometry",   "Image",         "SimpleMaterial",
      "SurfaceMaterial", "Light", "Camera",    "Background", "VolumeMaterial"};
  static_assert(!kNames.back().empty(), "a container type without its name");
  const auto i = static_cast<std::size_t>(t);
  return i < kNames.size() ? kNames[i] : kNames[0];
}

}  // namespace tsr::sg
