#pragma once
// The back-ends' shared vocabulary (backends/common) under the id pass's
// names: tsr::cov::Camera is tsr::backend::Camera, and so are Region,
// MeshId and InstanceId. The id pass never clips and ignores the camera's
// lens and shutter.
#include "tsr/backend/vocabulary.hpp"

namespace tsr::cov {
using namespace backend;
}  // namespace tsr::cov
