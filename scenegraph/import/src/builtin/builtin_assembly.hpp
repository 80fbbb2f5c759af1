#pragma once
// Small steps the built-in scenes share to fill a parsed::Scene by hand:
// a material, a light, a mesh, a node, a camera.
#include <optional>
#include <string>

#include "parsed_scene.hpp"

namespace tsr::sg::builtin {

parsed::Material material(std::string name, const Vec3& base, float metallic, float roughness);
parsed::Light light(std::string name, LightKind kind, const Vec3& color, float intensity);
// Adds a one-primitive mesh and returns its index.
int addMesh(parsed::Scene& s, parsed::Primitive p, int material, std::string name);
// A node (top-level unless `root` is false); `pose` is kept as the rest pose
// of animated nodes. Returns its index.
int addNode(parsed::Scene& s, std::string name, const Mat4& local, int mesh, int light = parsed::kNone,
            int camera = parsed::kNone, std::optional<Animation::Pose> pose = std::nullopt, bool root = true);
// A node matrix whose -Z axis points from `eye` towards `target`.
Mat4 lookFrom(const Vec3& eye, const Vec3& target, const Vec3& up = Vec3(0, 1, 0));
// A top-level node "camera" holding a pinhole camera.
void addCamera(parsed::Scene& s, const Vec3& eye, const Vec3& target, float fovDegrees, float znear, float zfar);

}  // namespace tsr::sg::builtin
