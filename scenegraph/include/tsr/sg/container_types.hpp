#pragma once
// Every concrete container type, once: the factory and the field tests
// are generated from this list.
#include <tuple>

#include "tsr/sg/background.hpp"
#include "tsr/sg/camera.hpp"
#include "tsr/sg/geometry.hpp"
#include "tsr/sg/image.hpp"
#include "tsr/sg/light.hpp"
#include "tsr/sg/parent_node.hpp"
#include "tsr/sg/simple_material.hpp"
#include "tsr/sg/surface_material.hpp"
#include "tsr/sg/volume_material.hpp"

namespace tsr::sg {

using ContainerTypes = std::tuple<Group, Transform, Geometry, Image, SimpleMaterial, SurfaceMaterial, Light, Camera,
                                  Background, VolumeMaterial>;
static_assert(std::tuple_size_v<ContainerTypes> == kContainerTypeCount);

}  // namespace tsr::sg
