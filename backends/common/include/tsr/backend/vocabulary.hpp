#pragma once
// Everything the back-ends' APIs share, for a back-end to take into its own
// namespace in its vocabulary.hpp (`using namespace tsr::backend;`): its
// own names, one definition for every back-end.
#include "tsr/backend/camera.hpp"
#include "tsr/backend/ids.hpp"
#include "tsr/backend/light.hpp"
#include "tsr/backend/primitive.hpp"
#include "tsr/backend/region.hpp"
#include "tsr/backend/vertex_edit.hpp"
