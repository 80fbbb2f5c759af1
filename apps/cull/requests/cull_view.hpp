#pragma once
// A decoded query as the renderers take it: its pose and field of view at
// its size, with the near and far planes of the scene's own camera (they
// fit the scene's scale).
#include "cull_query.hpp"
#include "tsr/med/view.hpp"

namespace tsr::app {

// Throws CullRequestError for a view no back-end could render (a pose
// that does not survive the float arithmetic of a look-at, say).
med::View cullView(const CullQuery& query, float nearPlane, float farPlane);

}  // namespace tsr::app
