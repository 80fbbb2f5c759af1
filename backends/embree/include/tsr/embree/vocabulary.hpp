#pragma once
// The back-ends' shared vocabulary (backends/common) under the path
// tracer's names: tsr::embree::Camera is tsr::backend::Camera, and so are
// Region, the ids and the lights. One definition, so a fix is made once.
#include "tsr/backend/vocabulary.hpp"

namespace tsr::embree {
using namespace backend;
}  // namespace tsr::embree
