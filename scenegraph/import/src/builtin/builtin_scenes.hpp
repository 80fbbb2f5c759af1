#pragma once
// Scenes made in code, for tests, demos and benchmarks without files.
#include <cstdint>
#include <string>

#include "parsed_scene.hpp"

namespace tsr::sg::builtin {

// The Cornell box of make_cornell.py, lit by an emissive ceiling quad, with
// a mirror sphere on the tall block and a glass sphere on the short one.
parsed::Scene cornell();
// The Cornell box with a glass sphere of scattering medium and a hazy room.
parsed::Scene cornellFog();
// `count` instances of a few shared meshes on a grid, a camera that sees
// them all and a directional light.
parsed::Scene instances(std::uint64_t count);
// The Cornell box with a cube sliding across the floor and a point light
// circling under the ceiling, as one looping 4-second animation.
parsed::Scene animated();

// The triangle budgets plant() accepts.
inline constexpr std::uint64_t kPlantMinTriangles = 1'000;
inline constexpr std::uint64_t kPlantMaxTriangles = 1'000'000'000;  // about 64 GB with the rasterizer
// A CAD-like industrial plant of about `triangles` triangles (within 10 % from
// 10,000 up): bays of tanks, pumps and motors in closed housings, pipe runs
// with elbows, flanges and valves, columns and walkways on floor slabs, on
// both sides of a main aisle. Every object is its own named node; more
// triangles buy more bays and finer tessellation. The camera stands in the
// aisle looking down it, so near objects hide far ones.
parsed::Scene plant(std::uint64_t triangles);

}  // namespace tsr::sg::builtin
