// builtin:plant:TRIANGLES — a large CAD-like model for culling and coverage.
//
// The plant is a grid of 20 m x 20 m bays on both sides of a main aisle
// that runs along +z. Each bay is planned from its own seed (its index), as
// a list of parts whose triangle counts are known before any mesh exists;
// bays are added until the budget is met, then laid out and meshed. The
// tessellation (segments around a circle) grows with the square root of the
// budget, so a bigger budget buys both more objects and rounder ones.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "builtin/builtin_assembly.hpp"
#include "builtin/builtin_scenes.hpp"
#include "builtin/mesh_shapes.hpp"

namespace tsr::sg::builtin {
namespace {

constexpr float kBay = 20.0f;     // a bay's side, metres
constexpr float kAisle = 8.0f;    // the main aisle's width
constexpr float kRackLow = 3.5f;  // pipe runs stay between these heights
constexpr float kRackHigh = 9.0f;

enum PlantMaterial {
  kConcrete,
  kSteel,
  kSafetyYellow,
  kStainless,
  kRedPipe,
  kBluePipe,
  kGreyPipe,
  kValveRed,
  kHousingGrey,
  kPumpGreen,
  kMotorBlue,
  kCabinet,
  kPlantMaterialCount
};

// What an object is made of, countable before it is meshed.
struct Shape {
  enum class Kind { Box, Lathe, Bend } kind = Kind::Box;
  Vec3 half{0.0f};            // Box: half extents
  std::vector<Vec2> profile;  // Lathe: (radius, y) points
  float major = 0.0f;         // Bend: a quarter torus
  float minor = 0.0f;
  int segments = 0;      // Lathe: around the axis; Bend: around the tube
  int bendSegments = 0;  // Bend: along the bend
};

struct Part {
  std::string name;
  int material = kSteel;
  Mat4 pose{1.0f};  // bay-local
  Shape shape;
};

std::size_t triangles(const Shape& s) {
  switch (s.kind) {
    case Shape::Kind::Box:
      return 12;
    case Shape::Kind::Lathe:
      return shapes::latheTriangles(s.profile, s.segments);
    case Shape::Kind::Bend:
      return 2u * static_cast<std::size_t>(s.bendSegments) * static_cast<std::size_t>(s.segments);
  }
  return 0;
}

parsed::Primitive shaped(const Shape& s) {
  switch (s.kind) {
    case Shape::Kind::Box:
      return shapes::box(s.half);
    case Shape::Kind::Lathe:
      return shapes::lathe(s.profile, s.segments);
    case Shape::Kind::Bend:
      return shapes::torus(s.major, s.minor, s.bendSegments, s.segments, glm::half_pi<float>());
  }
  return {};
}

// Nothing in the plant is textured, so its meshes carry no uvs, as a CAD
// tessellation has none: a quarter of their vertex bytes.
parsed::Primitive mesh(const Shape& s) {
  parsed::Primitive p = shaped(s);
  std::vector<Vec2>().swap(p.uvs);  // its memory too, not only its elements
  return p;
}

Shape box(const Vec3& half) {
  Shape s;
  s.half = half;
  return s;
}

Shape lathe(std::vector<Vec2> profile, int segments) {
  Shape s;
  s.kind = Shape::Kind::Lathe;
  s.profile = std::move(profile);
  s.segments = segments;
  return s;
}

// A closed cylinder of radius r from y = 0 to y = length.
Shape cylinder(float r, float length, int segments) {
  return lathe({{0, 0}, {r, 0}, {r, length}, {0, length}}, segments);
}

Mat4 translation(const Vec3& t) { return glm::translate(Mat4(1.0f), t); }

// Local x, y, z onto ex, ey, ez (a right-handed orthonormal set) at origin.
Mat4 frame(const Vec3& origin, const Vec3& ex, const Vec3& ey, const Vec3& ez) {
  return Mat4(Vec4(ex, 0), Vec4(ey, 0), Vec4(ez, 0), Vec4(origin, 1));
}

// Local y onto the unit vector `axis`, starting at `origin`.
Mat4 alongAxis(const Vec3& origin, const Vec3& axis) {
  const Vec3 helper = std::abs(axis.y) < 0.9f ? Vec3(0, 1, 0) : Vec3(1, 0, 0);
  const Vec3 ex = glm::normalize(glm::cross(axis, helper));
  return frame(origin, ex, axis, glm::cross(ex, axis));
}

const Vec3 kAxes[] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};

// Plans bays one at a time; object numbers run on across bays so every name
// is unique.
class BayPlanner {
 public:
  explicit BayPlanner(int segments) : segments_(segments) {}

  std::vector<Part> bay(std::uint64_t index) {
    rng_.seed(0x9E3779B97F4A7C15ull * (index + 1) ^ 0x5DEECE66Dull);
    parts_.clear();
    const std::string bay = std::to_string(index + 1);
    structure(bay);
    if (uniform(0, 1) < 0.7f) {
      tank({6, 0, 10}, uniform(2.0f, 3.6f));
    } else {
      tank({6, 0, 5.5f}, uniform(1.5f, 3.2f));
      tank({6, 0, 14.5f}, uniform(1.5f, 3.2f));
    }
    const int housings = 1 + pick(3);
    for (int k = 0; k < housings; ++k)
      housing(kBay * (static_cast<float>(k) + 0.5f) / static_cast<float>(housings),
              kBay / static_cast<float>(housings));
    const int runs = 2 + pick(4);
    for (int k = 0; k < runs; ++k) pipeRun();
    return std::move(parts_);
  }

 private:
  // Deterministic on every platform (std::uniform_*_distribution is not).
  float uniform(float lo, float hi) { return lo + (hi - lo) * static_cast<float>(rng_() >> 40) * 0x1p-24f; }
  int pick(int n) { return static_cast<int>(rng_() % static_cast<std::uint64_t>(n)); }

  void add(std::string name, int material, const Mat4& pose, Shape shape) {
    parts_.push_back({std::move(name), material, pose, std::move(shape)});
  }

  // Floor slab, four columns, maybe a walkway, junction boxes on columns.
  void structure(const std::string& bay) {
    add("slab-" + bay, kConcrete, translation({10, -0.15f, 10}), box({10, 0.15f, 10}));
    const Vec2 corners[] = {{0.5f, 0.5f}, {19.5f, 0.5f}, {0.5f, 19.5f}, {19.5f, 19.5f}};
    for (int k = 0; k < 4; ++k)
      add("column-" + bay + "-" + std::to_string(k + 1), kSteel, translation({corners[k].x, 5, corners[k].y}),
          box({0.2f, 5, 0.2f}));
    if (uniform(0, 1) < 0.5f) {
      add("walkway-" + bay, kSteel, translation({1.35f, 4, 10}), box({0.55f, 0.04f, 9.3f}));
      for (int k = 0; k < 2; ++k)
        add("railing-" + bay + "-" + std::to_string(k + 1), kSafetyYellow,
            translation({0.85f + static_cast<float>(k), 5, 10}), box({0.03f, 0.03f, 9.3f}));
    }
    const int boxes = 1 + pick(3);
    for (int k = 0; k < boxes; ++k) {
      const Vec2 c = corners[pick(4)];
      const float side = c.y < 10 ? 1 : -1;  // on the column's face towards the bay
      const Vec3 at(c.x, uniform(1.2f, 1.8f), c.y + side * 0.3f);
      const std::string name = "junction-box-" + std::to_string(++junctionBoxes_);
      add(name, kCabinet, translation(at), box({0.2f, 0.25f, 0.1f}));
      add("terminal-block-" + std::to_string(junctionBoxes_) + " (in " + name + ")", kGreyPipe, translation(at),
          box({0.15f, 0.2f, 0.06f}));
    }
  }

  // A vertical tank with a dished head, an agitator inside and nozzles.
  void tank(const Vec3& base, float radius) {
    const std::string name = "tank-" + std::to_string(++tanks_);
    const float height = uniform(4, 14), head = 0.35f * radius;
    std::vector<Vec2> profile = {{0, 0}, {radius, 0}, {radius, height}};
    const int rings = std::max(2, segments_ / 6);
    for (int k = 1; k <= rings; ++k) {
      const float a = glm::half_pi<float>() * static_cast<float>(k) / static_cast<float>(rings);
      profile.emplace_back(k == rings ? 0.0f : radius * std::cos(a), height + head * std::sin(a));
    }
    add(name, kStainless, translation(base), lathe(std::move(profile), 2 * segments_));
    const int thin = std::max(6, segments_ / 4);
    const std::string inside = " (in " + name + ")";
    add("agitator-" + std::to_string(tanks_) + inside, kSteel, translation(base + Vec3(0, 0.6f, 0)),
        cylinder(0.06f, height - 0.8f, thin));
    add("impeller-" + std::to_string(tanks_) + inside, kSteel, translation(base + Vec3(0, 0.9f, 0)),
        box({0.6f * radius, 0.04f, 0.12f}));
    for (int k = 0; k < 2; ++k) {
      const float a = uniform(0, glm::two_pi<float>());
      const Vec3 out(std::cos(a), 0, std::sin(a));
      const Vec3 at = base + Vec3(0, uniform(0.8f, height - 0.5f), 0) + (radius - 0.1f) * out;
      add("nozzle-" + std::to_string(tanks_) + "-" + std::to_string(k + 1), kStainless, alongAxis(at, out),
          cylinder(uniform(0.08f, 0.2f), 0.5f, std::max(6, segments_ / 2)));
    }
  }

  // A closed housing around a pump and its motor on a base plate.
  void housing(float z, float slot) {
    const std::string name = "housing-" + std::to_string(++housings_);
    const Vec3 half(uniform(1.2f, 2.0f), uniform(0.9f, 1.4f), uniform(0.8f, std::min(1.3f, 0.5f * slot - 0.5f)));
    const Vec3 centre(15, half.y, z);
    add(name, kHousingGrey, translation(centre), box(half));
    const std::string inside = " (in " + name + ")", number = std::to_string(housings_);
    add("baseplate-" + number + inside, kSteel, translation({centre.x, 0.05f, z}),
        box({half.x - 0.15f, 0.05f, half.z - 0.15f}));
    const float r = 0.8f * std::min(half.z - 0.15f, half.y - 0.2f);
    const float axisY = 0.1f + r;
    const float pumpLength = half.x - 0.25f;
    add("pump-" + number + inside, kPumpGreen, alongAxis({centre.x - half.x + 0.2f, axisY, z}, {1, 0, 0}),
        lathe({{0, 0},
               {0.6f * r, 0},
               {0.6f * r, 0.15f * pumpLength},
               {r, 0.3f * pumpLength},
               {r, 0.7f * pumpLength},
               {0.6f * r, 0.85f * pumpLength},
               {0.6f * r, pumpLength},
               {0, pumpLength}},
              segments_));
    add("motor-" + number + inside, kMotorBlue, alongAxis({centre.x + 0.05f, axisY, z}, {1, 0, 0}),
        cylinder(0.85f * r, half.x - 0.25f, segments_));
  }

  // How far `p` may travel along `d` and stay `margin` inside the pipe rack.
  static float room(const Vec3& p, const Vec3& d, float margin) {
    const Vec3 lo(10.5f + margin, kRackLow + margin, 0.2f + margin),
        hi(19.8f - margin, kRackHigh - margin, 19.8f - margin);
    float t = 1e9f;
    for (int i = 0; i < 3; ++i) {
      if (d[i] > 0) t = std::min(t, (hi[i] - p[i]) / d[i]);
      if (d[i] < 0) t = std::min(t, (lo[i] - p[i]) / d[i]);
    }
    return t;
  }

  // Straight pipes joined by elbows (turns) or flanges, with some valves,
  // inside the bay's pipe rack (above the housings, clear of the tanks).
  void pipeRun() {
    const std::string run = std::to_string(++runs_);
    const float radii[] = {0.05f, 0.08f, 0.1f, 0.15f, 0.2f, 0.3f};
    const float r = radii[pick(6)];
    const int materials[] = {kRedPipe, kBluePipe, kGreyPipe, kStainless, kSafetyYellow};
    const int material = materials[pick(5)];
    const float bend = std::max(2.5f * r, 0.2f);
    Vec3 p, d;
    if (pick(2) == 0) {
      p = {uniform(11.5f, 19), uniform(kRackLow + 0.5f, kRackHigh - 0.5f), 0.01f};
      d = {0, 0, 1};
    } else {
      p = {19.99f, uniform(kRackLow + 0.5f, kRackHigh - 0.5f), uniform(1, 19)};
      d = {-1, 0, 0};
    }
    const int segments = 3 + pick(5);
    for (int k = 1; k <= segments; ++k) {
      const float length = std::min(uniform(1.5f, 6), room(p, d, bend + r));
      if (length < 0.5f) break;
      const std::string id = run + "-" + std::to_string(k);
      add("pipe-" + id, material, alongAxis(p, d), lathe({{r, 0}, {r, length}}, segments_));
      if (uniform(0, 1) < 0.3f) valve("valve-" + id, p + 0.5f * length * d, d, r);
      p += length * d;
      if (k == segments) break;
      // Turn where there is room, else go on straight through a flange.
      Vec3 options[4];
      int count = 0;
      for (const Vec3& axis : kAxes)
        if (std::abs(glm::dot(axis, d)) < 0.5f && room(p + bend * (d + axis), axis, bend + r) > 1.5f)
          options[count++] = axis;
      if (count == 0 || uniform(0, 1) < 0.35f) {
        const float t = 0.3f * r + 0.03f;
        add("flange-" + id, material, alongAxis(p - 0.5f * t * d, d), cylinder(1.6f * r, t, segments_));
        continue;
      }
      const Vec3 turn = options[pick(count)];
      Shape elbow;
      elbow.kind = Shape::Kind::Bend;
      elbow.major = bend;
      elbow.minor = r;
      elbow.segments = segments_;
      elbow.bendSegments = std::max(2, segments_ / 4);
      // The torus bends from local +x towards +z: start tangent +z is d,
      // the start point sits at local +x, -turn from the bend's centre.
      add("elbow-" + id, material, frame(p + bend * turn, -turn, glm::cross(d, -turn), d), std::move(elbow));
      p += bend * (d + turn);
      d = turn;
    }
  }

  // A flanged valve body around the pipe, centred on `at`.
  void valve(std::string name, const Vec3& at, const Vec3& d, float r) {
    const float v = std::max(r, 0.1f), f = std::max(1.8f * r, 1.6f * v), length = 2.4f * v;
    add(std::move(name), kValveRed, alongAxis(at - 0.5f * length * d, d),
        lathe({{0, 0},
               {f, 0},
               {f, 0.3f * v},
               {1.4f * v, 0.3f * v},
               {1.7f * v, 1.2f * v},
               {1.4f * v, 2.1f * v},
               {f, 2.1f * v},
               {f, length},
               {0, length}},
              segments_));
  }

  int segments_;
  std::mt19937_64 rng_;
  std::vector<Part> parts_;
  int tanks_ = 0, housings_ = 0, runs_ = 0, junctionBoxes_ = 0;
};

// Segments around a circle for a budget: 6 for small budgets, up to 64.
int segmentsFor(std::uint64_t budget) {
  const auto s = 2 * static_cast<int>(std::lround(std::sqrt(static_cast<double>(budget)) / 80.0));
  return std::clamp(s, 6, 64);
}

void addPlantMaterials(parsed::Scene& s) {
  s.materials.resize(kPlantMaterialCount);
  s.materials[kConcrete] = material("concrete", Vec3(0.55f, 0.54f, 0.5f), 0.0f, 0.9f);
  s.materials[kSteel] = material("painted steel", Vec3(0.35f, 0.38f, 0.42f), 0.3f, 0.6f);
  s.materials[kSafetyYellow] = material("safety yellow", Vec3(0.95f, 0.75f, 0.1f), 0.0f, 0.5f);
  s.materials[kStainless] = material("stainless steel", Vec3(0.8f, 0.8f, 0.82f), 1.0f, 0.3f);
  s.materials[kRedPipe] = material("fire water red", Vec3(0.75f, 0.1f, 0.08f), 0.0f, 0.5f);
  s.materials[kBluePipe] = material("cooling water blue", Vec3(0.15f, 0.35f, 0.75f), 0.0f, 0.5f);
  s.materials[kGreyPipe] = material("process grey", Vec3(0.6f, 0.6f, 0.6f), 0.2f, 0.5f);
  s.materials[kValveRed] = material("valve red", Vec3(0.85f, 0.15f, 0.1f), 0.0f, 0.4f);
  s.materials[kHousingGrey] = material("housing grey", Vec3(0.7f, 0.72f, 0.7f), 0.0f, 0.7f);
  s.materials[kPumpGreen] = material("pump green", Vec3(0.2f, 0.55f, 0.3f), 0.0f, 0.5f);
  s.materials[kMotorBlue] = material("motor blue", Vec3(0.1f, 0.25f, 0.6f), 0.0f, 0.5f);
  s.materials[kCabinet] = material("cabinet beige", Vec3(0.85f, 0.8f, 0.65f), 0.0f, 0.6f);
}

}  // namespace

parsed::Scene plant(std::uint64_t budget) {
  // Plan bays until the next one would overshoot more than stopping short.
  BayPlanner planner(segmentsFor(budget));
  std::vector<std::vector<Part>> bays;
  std::uint64_t total = 12;  // the aisle's floor
  std::size_t parts = 0;
  while (total < budget) {
    std::vector<Part> bay = planner.bay(bays.size());
    std::uint64_t t = 0;
    for (const Part& p : bay) t += triangles(p.shape);
    if (!bays.empty() && total + t > budget && total + t - budget > budget - total) break;
    total += t;
    parts += bay.size();
    bays.push_back(std::move(bay));
  }

  // Columns of bays left and right of the aisle (x = 0), rows along +z.
  const auto columns = static_cast<std::size_t>(std::max(2.0, std::ceil(std::sqrt(static_cast<double>(bays.size())))));
  const std::size_t rows = (bays.size() + columns - 1) / columns, left = columns / 2;
  const float depth = kBay * static_cast<float>(rows);

  parsed::Scene s;
  addPlantMaterials(s);
  s.primitives.reserve(parts + 1);
  s.meshes.reserve(parts + 1);
  s.nodes.reserve(parts + 3);
  s.roots.reserve(parts + 3);
  addNode(s, "aisle-floor", translation({0, -0.1f, 0.5f * depth}),
          addMesh(s, shapes::box({0.5f * kAisle, 0.1f, 0.5f * depth}), kConcrete, "aisle-floor"));
  for (std::size_t i = 0; i < bays.size(); ++i) {
    const std::size_t column = i % columns, row = i / columns;
    const float x = column < left ? -0.5f * kAisle - kBay * static_cast<float>(left - column)
                                  : 0.5f * kAisle + kBay * static_cast<float>(column - left);
    const Mat4 origin = translation({x, 0, kBay * static_cast<float>(row)});
    for (Part& p : bays[i]) {
      const int m = addMesh(s, mesh(p.shape), p.material, p.name);
      addNode(s, std::move(p.name), origin * p.pose, m);
    }
  }

  // Standing in the aisle at eye height, looking down it.
  addCamera(s, Vec3(0, 1.7f, 2), Vec3(0, 2.5f, depth), 60.0f, 0.05f, 2.0f * depth + 200.0f);
  s.lights.push_back(light("sun", LightKind::Directional, Vec3(1.0f, 0.97f, 0.9f), 1.6f));
  addNode(s, "sun", lookFrom(Vec3(0), Vec3(-0.4f, -1.0f, 0.3f)), parsed::kNone, 0);
  s.background = Vec3(0.3f, 0.4f, 0.55f);
  return s;
}

}  // namespace tsr::sg::builtin
