// Every container type's fields, generated from their declarations
// (fieldSpecs() over sg::ContainerTypes): the numbers are pinned, and every
// setter's change reaches a replica through commit, the wire and apply.
#include <gtest/gtest.h>

#include <functional>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>

#include "tsr/sg/container_factory.hpp"
#include "tsr/sg/container_types.hpp"
#include "tsr/sg/scene.hpp"
#include "tsr/sg/wire/wire_codec.hpp"

using namespace tsr::sg;

namespace {

template <class Fn, class... T>
void forEachTypeIn(Fn&& fn, std::tuple<T...>*) {
  (fn(static_cast<T*>(nullptr)), ...);
}
template <class Fn>
void forEachType(Fn&& fn) {
  forEachTypeIn(fn, static_cast<ContainerTypes*>(nullptr));
}

const char* kindName(FieldKind k) {
  switch (k) {
    case FieldKind::Value:
      return "value";
    case FieldKind::Reference:
      return "reference";
    case FieldKind::Array:
      return "array";
  }
  return "?";
}

// Creates a container of the first type in `allowed`, for a reference.
ContainerId createTarget(Scene& scene, TypeSet allowed) {
  ContainerId id = kNoContainer;
  forEachType([&]<class T>(T*) {
    if (id == kNoContainer && (allowed & typeBit(T::kType))) id = scene.create<T>("target").id();
  });
  return id;
}

// A value unlike every default, valid for every field that holds its type.
template <class V>
V sampleValue(Scene& scene, TypeSet allowed) {
  if constexpr (std::is_same_v<V, float>) {
    return 0.375f;
  } else if constexpr (std::is_same_v<V, Vec2>) {
    return {0.25f, 0.5f};
  } else if constexpr (std::is_same_v<V, Vec3>) {
    return {0.25f, 0.5f, 0.125f};
  } else if constexpr (std::is_same_v<V, Vec4>) {
    return {0.25f, 0.5f, 0.125f, 0.75f};
  } else if constexpr (std::is_same_v<V, Mat4>) {
    return glm::translate(Mat4(1.0f), Vec3(1, 2, 3));
  } else if constexpr (std::is_same_v<V, std::uint32_t>) {
    return 3;
  } else if constexpr (std::is_enum_v<V>) {
    return static_cast<V>(1);
  } else if constexpr (std::is_same_v<V, std::string>) {
    return "field-test";
  } else if constexpr (std::is_same_v<V, ContainerId>) {
    return createTarget(scene, allowed);
  } else if constexpr (std::is_same_v<V, std::vector<ContainerId>>) {
    return {createTarget(scene, allowed)};
  } else if constexpr (std::is_same_v<V, std::vector<std::uint32_t>>) {
    return {0, 1, 2};
  } else if constexpr (std::is_same_v<V, std::vector<std::uint8_t>>) {
    return {1, 2, 3};
  } else if constexpr (requires { typename V::Elements; }) {  // a SharedArray
    return V(sampleValue<typename V::Elements>(scene, allowed));
  } else {
    using E = typename V::value_type;
    return V(3, sampleValue<E>(scene, allowed));
  }
}

// What a setter takes for a member's value: a shared array's elements.
template <class V>
decltype(auto) setterArgument(const V& v) {
  if constexpr (requires { typename V::Elements; })
    return v.get().toVector();
  else
    return (v);
}

std::vector<std::uint8_t> fieldBytes(const Container& c, FieldIndex f) {
  std::vector<std::uint8_t> bytes;
  ByteWriter w(bytes);
  c.writeField(f, w, nullptr);
  return bytes;
}

// Encodes the frame, decodes it and applies it to the replica; returns the
// entry of container `id` (or a default entry when the frame has none).
ChangeEntry shipFrame(Scene& source, Scene& replica, ContainerId id) {
  ChangeListPtr list = source.commit();
  replica.apply(*decode(encode(*list)));
  for (const ChangeEntry& e : list->changes())
    if (e.id == id) return e;
  return {};
}

void expectReplicaEqual(const Container& source, const Scene& replica, const std::string& what) {
  const Container* copy = replica.find(source.id());
  ASSERT_NE(copy, nullptr) << what;
  for (FieldIndex f = 0; f < source.fieldCount(); ++f)
    EXPECT_EQ(fieldBytes(source, f), fieldBytes(*copy, f)) << what << ": field " << source.fieldInfo(f).name;
}

}  // namespace

TEST(FieldDeclarations, NumbersArePinned) {
  std::ostringstream table;
  forEachType([&]<class T>(T*) {
    const Container& c = prototype(T::kType);
    table << typeName(T::kType) << ":";
    for (FieldIndex f = Container::kFirstOwnField; f < c.fieldCount(); ++f)
      table << " " << int(f) << "=" << c.fieldInfo(f).name << "/" << kindName(c.fieldInfo(f).kind);
    table << "\n";
  });
  // The wire numbers: change a line only with a protocol version bump.
  EXPECT_EQ(table.str(),
            "Group: 2=children/reference\n"
            "Transform: 2=children/reference 3=matrix/value 4=frameMotion/value\n"
            "Geometry: 2=positions/array 3=normals/array 4=uvs/array 5=colors/array 6=indices/array "
            "7=material/reference 8=motion/value 9=volume/reference 10=primitive/value\n"
            "Image: 2=width/value 3=height/value 4=channels/value 5=format/value 6=colorSpace/value "
            "7=pixels/array 8=uri/value\n"
            "SimpleMaterial: 2=diffuse/value 3=diffuseTexture/reference 4=specular/value 5=shininess/value "
            "6=emission/value 7=transparency/value\n"
            "SurfaceMaterial: 2=baseColor/value 3=baseColorTexture/reference 4=opacity/value 5=metallic/value "
            "6=roughness/value 7=metallicRoughnessTexture/reference 8=specular/value 9=specularTexture/reference "
            "10=emission/value 11=emissionStrength/value 12=emissionTexture/reference 13=transmission/value "
            "14=transmissionTexture/reference 15=ior/value 16=normalTexture/reference 17=normalScale/value "
            "18=alphaMode/value 19=alphaCutoff/value 20=occlusionTexture/reference 21=occlusionStrength/value "
            "22=uvTransforms/array\n"
            "Light: 2=kind/value 3=color/value 4=intensity/value 5=position/value 6=direction/value "
            "7=innerConeAngle/value 8=outerConeAngle/value\n"
            "Camera: 2=pose/value 3=verticalFov/value 4=near/value 5=far/value 6=eyeSeparation/value "
            "7=zeroParallaxDistance/value 8=apertureRadius/value 9=focusDistance/value 10=shutterOpen/value "
            "11=shutterClose/value\n"
            "Background: 2=kind/value 3=color/value 4=gradientTop/value 5=gradientBottom/value "
            "6=environment/reference 7=intensity/value 8=medium/reference\n"
            "VolumeMaterial: 2=emission/value 3=emissionTexture/reference 4=absorption/value "
            "5=absorptionTexture/reference 6=scattering/value 7=scatteringTexture/reference 8=phaseG/value "
            "9=textureSlices/value\n");
}

TEST(FieldDeclarations, EverySetterReachesAReplicaThroughTheWire) {
  int setters = 0;
  forEachType([&]<class T>(T*) {
    std::apply(
        [&](const auto&... spec) {
          (
              [&] {
                const std::string what = std::string(typeName(T::kType)) + "." + std::string(spec.name);
                Scene source, replica;
                T& c = source.template create<T>("c");
                shipFrame(source, replica, c.id());
                using V = std::decay_t<decltype(c.*spec.member)>;
                V value = sampleValue<V>(source, spec.allowedTargets);
                std::invoke(spec.setter, c, setterArgument(value));
                EXPECT_EQ(c.*spec.member, value) << what << ": the setter did not store the value";
                ChangeEntry entry = shipFrame(source, replica, c.id());
                EXPECT_TRUE(entry.changed(spec.number)) << what << ": the setter did not mark its field";
                // A setter of one field marks that field alone; the image's
                // layout fields change together (see Image::fieldSpecs).
                if constexpr (std::is_member_function_pointer_v<decltype(spec.setter)>) {
                  EXPECT_EQ(entry.mask, fieldBit(spec.number)) << what << ": the setter marked other fields";
                }
                expectReplicaEqual(c, replica, what);
                EXPECT_EQ(replica.contentHash(), source.contentHash()) << what;
                ++setters;
              }(),
              ...);
        },
        T::fieldSpecs());
  });
  EXPECT_EQ(setters, 79);  // the own fields of all ten types, as pinned above
}

TEST(FieldDeclarations, NamesAndAttachmentsOfEveryTypeReachAReplica) {
  forEachType([&]<class T>(T*) {
    const std::string what(typeName(T::kType));
    Scene source, replica;
    T& c = source.template create<T>("c");
    shipFrame(source, replica, c.id());
    c.setName("renamed");
    EXPECT_EQ(shipFrame(source, replica, c.id()).mask, fieldBit(Container::kName)) << what;
    c.setAttachment("test.key", std::int64_t{7});
    EXPECT_EQ(shipFrame(source, replica, c.id()).mask, fieldBit(Container::kAttachments)) << what;
    c.removeAttachment("test.key");
    EXPECT_EQ(shipFrame(source, replica, c.id()).mask, fieldBit(Container::kAttachments)) << what;
    expectReplicaEqual(c, replica, what);
  });
}

TEST(FieldDeclarations, RangeAndChildEditsReachAReplica) {
  Scene source, replica;
  Geometry& g = source.create<Geometry>("g");
  g.setPositions({Vec3(0), Vec3(1), Vec3(2)});
  g.setNormals({Vec3(0, 1, 0), Vec3(0, 1, 0), Vec3(0, 1, 0)});
  g.setUvs({Vec2(0), Vec2(1), Vec2(0.5f)});
  g.setColors({Vec4(1), Vec4(1), Vec4(1)});
  g.setIndices({0, 1, 2});
  Group& parent = source.create<Group>("parent");
  Group& child = source.create<Group>("child");
  shipFrame(source, replica, g.id());

  const Vec3 up[] = {Vec3(0, 0, 1)};
  g.updatePositions(1, up);
  g.updateNormals(2, up);
  const Vec2 uv[] = {Vec2(0.25f)};
  g.updateUvs(0, uv);
  const Vec4 colour[] = {Vec4(0.5f)};
  g.updateColors(1, colour);
  const std::uint32_t index[] = {0};
  g.updateIndices(2, index);
  EXPECT_EQ(shipFrame(source, replica, g.id()).mask, fieldBit(Geometry::Positions) | fieldBit(Geometry::Normals) |
                                                         fieldBit(Geometry::Uvs) | fieldBit(Geometry::Colors) |
                                                         fieldBit(Geometry::Indices));
  expectReplicaEqual(g, replica, "Geometry ranges");

  parent.addChild(child.id());
  EXPECT_EQ(shipFrame(source, replica, parent.id()).mask, fieldBit(Group::Children));
  expectReplicaEqual(parent, replica, "Group.addChild");
  parent.removeChild(child.id());
  EXPECT_EQ(shipFrame(source, replica, parent.id()).mask, fieldBit(Group::Children));
  expectReplicaEqual(parent, replica, "Group.removeChild");
  EXPECT_EQ(replica.contentHash(), source.contentHash());
}
