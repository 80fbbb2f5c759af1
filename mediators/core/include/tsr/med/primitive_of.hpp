#pragma once
// What a geometry's indices draw, in the back-ends' words.
#include "tsr/backend/primitive.hpp"
#include "tsr/sg/geometry.hpp"

namespace tsr::med {

inline backend::Primitive primitiveOf(const sg::Geometry& g) {
  switch (g.primitive()) {
    case sg::GeometryPrimitive::Lines:
      return backend::Primitive::Lines;
    case sg::GeometryPrimitive::Points:
      return backend::Primitive::Points;
    default:
      return backend::Primitive::Triangles;
  }
}

}  // namespace tsr::med
