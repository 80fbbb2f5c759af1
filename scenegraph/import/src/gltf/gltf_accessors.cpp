#include "gltf/gltf_accessors.hpp"

#include <cmath>
#include <cstring>
#include <functional>

namespace tsr::sg::gltf {
namespace {

int componentCount(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return 1;
    case TINYGLTF_TYPE_VEC2:
      return 2;
    case TINYGLTF_TYPE_VEC3:
      return 3;
    case TINYGLTF_TYPE_VEC4:
    case TINYGLTF_TYPE_MAT2:
      return 4;
    case TINYGLTF_TYPE_MAT3:
      return 9;
    case TINYGLTF_TYPE_MAT4:
      return 16;
    default:
      return 0;
  }
}

int componentSize(int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      return 0;
  }
}

template <class T>
T load(const std::uint8_t* p) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  return v;
}

// One component as a float; normalized integers as glTF's spec maps them.
float decodeFloat(const std::uint8_t* p, int componentType, bool normalized) {
  float v = 0.0f;
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return load<float>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      v = load<std::uint8_t>(p);
      break;
    case TINYGLTF_COMPONENT_TYPE_BYTE:
      v = load<std::int8_t>(p);
      break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      v = load<std::uint16_t>(p);
      break;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
      v = load<std::int16_t>(p);
      break;
    default:
      return static_cast<float>(load<std::uint32_t>(p));
  }
  return normalized ? normalizedInteger(v, componentType) : v;
}

std::uint32_t decodeIndex(const std::uint8_t* p, int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return load<std::uint8_t>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return load<std::uint16_t>(p);
    default:
      return load<std::uint32_t>(p);
  }
}

struct Layout {
  const std::uint8_t* base = nullptr;  // null: no buffer view, all zeros
  std::size_t stride = 0;
  std::size_t count = 0;
  int components = 0;
  int componentType = 0;
  bool normalized = false;
};

}  // namespace

void AccessorReader::fail(const std::string& reason) const { throw ImportError(source_, reason); }

const tinygltf::Accessor& AccessorReader::accessor(int index, const std::string& what) const {
  if (index < 0 || static_cast<std::size_t>(index) >= model_.accessors.size())
    fail(what + " names accessor " + std::to_string(index) + ", but there are " +
         std::to_string(model_.accessors.size()) + " accessors");
  return model_.accessors[static_cast<std::size_t>(index)];
}

std::size_t AccessorReader::count(int index, const std::string& what) const { return accessor(index, what).count; }

std::vector<std::uint8_t> AccessorReader::viewBytes(int index, const std::string& what) const {
  if (index < 0 || static_cast<std::size_t>(index) >= model_.bufferViews.size())
    fail(what + " names buffer view " + std::to_string(index) + ", but there are " +
         std::to_string(model_.bufferViews.size()));
  const tinygltf::BufferView& view = model_.bufferViews[static_cast<std::size_t>(index)];
  if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model_.buffers.size())
    fail("buffer view " + std::to_string(index) + " names buffer " + std::to_string(view.buffer) +
         ", which does not exist");
  const auto& data = model_.buffers[static_cast<std::size_t>(view.buffer)].data;
  if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset)
    fail("buffer view " + std::to_string(index) + " covers bytes [" + std::to_string(view.byteOffset) + ", +" +
         std::to_string(view.byteLength) + ") of buffer " + std::to_string(view.buffer) + ", which has " +
         std::to_string(data.size()) + " bytes");
  return {data.begin() + static_cast<std::ptrdiff_t>(view.byteOffset),
          data.begin() + static_cast<std::ptrdiff_t>(view.byteOffset + view.byteLength)};
}

// Shared by floats() and indices(): resolves and bounds-checks where the
// elements of a dense accessor lie. Sparse substitution is done by callers.
static Layout layoutOf(const tinygltf::Model& model, const tinygltf::Accessor& acc, int index,
                       const ImportOptions& options, const std::function<void(const std::string&)>& fail) {
  Layout l;
  const std::string name = "accessor " + std::to_string(index);
  l.components = componentCount(acc.type);
  if (!l.components) fail(name + " has an unknown type");
  const int size = componentSize(acc.componentType);
  if (!size) fail(name + " has an unknown component type " + std::to_string(acc.componentType));
  l.componentType = acc.componentType;
  l.normalized = acc.normalized;
  l.count = acc.count;
  if (acc.count > options.maxAccessorElements)
    fail(name + " has " + std::to_string(acc.count) + " elements, more than the limit of " +
         std::to_string(options.maxAccessorElements));
  if (acc.bufferView < 0) return l;

  if (static_cast<std::size_t>(acc.bufferView) >= model.bufferViews.size())
    fail(name + " names buffer view " + std::to_string(acc.bufferView) + ", but there are " +
         std::to_string(model.bufferViews.size()));
  const tinygltf::BufferView& view = model.bufferViews[static_cast<std::size_t>(acc.bufferView)];
  if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model.buffers.size())
    fail("buffer view " + std::to_string(acc.bufferView) + " names buffer " + std::to_string(view.buffer) +
         ", which does not exist");
  const auto& data = model.buffers[static_cast<std::size_t>(view.buffer)].data;
  if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset)
    fail("buffer view " + std::to_string(acc.bufferView) + " covers bytes [" + std::to_string(view.byteOffset) + ", +" +
         std::to_string(view.byteLength) + ") of buffer " + std::to_string(view.buffer) + ", which has " +
         std::to_string(data.size()) + " bytes");
  const std::size_t elementSize = static_cast<std::size_t>(size) * static_cast<std::size_t>(l.components);
  l.stride = view.byteStride ? view.byteStride : elementSize;
  if (l.stride < elementSize || l.stride > 252)
    fail("buffer view " + std::to_string(acc.bufferView) + " has byte stride " + std::to_string(l.stride) +
         ", which does not fit " + name + "'s " + std::to_string(elementSize) + "-byte elements");
  // count and stride are bounded, so this cannot overflow 64 bits.
  const std::uint64_t end =
      acc.count == 0 ? acc.byteOffset : acc.byteOffset + (acc.count - 1) * std::uint64_t{l.stride} + elementSize;
  if (acc.byteOffset > view.byteLength || end > view.byteLength)
    fail(name + " reads bytes [" + std::to_string(acc.byteOffset) + ", " + std::to_string(end) + ") of buffer view " +
         std::to_string(acc.bufferView) + ", which has " + std::to_string(view.byteLength) + " bytes");
  l.base = data.data() + view.byteOffset + acc.byteOffset;
  return l;
}

std::vector<float> AccessorReader::floats(int index, int components, bool normalizedInts,
                                          const std::string& what) const {
  const tinygltf::Accessor& acc = accessor(index, what);
  const std::string name = "accessor " + std::to_string(index) + " (" + what + ")";
  auto failFn = [&](const std::string& r) { fail(r + " (" + what + ")"); };
  const Layout l = layoutOf(model_, acc, index, options_, failFn);
  if (l.components != components)
    fail(name + " has " + std::to_string(l.components) + " components per element, expected " +
         std::to_string(components));
  if (l.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !(normalizedInts && l.normalized) && !quantized_)
    fail(name + " must hold floats" + std::string(normalizedInts ? " or normalized integers" : ""));
  if (l.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) fail(name + ": 32-bit integers cannot be normalized");

  const std::size_t cs = static_cast<std::size_t>(componentSize(l.componentType));
  std::vector<float> out(l.count * static_cast<std::size_t>(components), 0.0f);
  if (l.base)
    for (std::size_t i = 0; i < l.count; ++i)
      for (std::size_t c = 0; c < static_cast<std::size_t>(components); ++c)
        out[i * static_cast<std::size_t>(components) + c] =
            decodeFloat(l.base + i * l.stride + c * cs, l.componentType, l.normalized);

  if (acc.sparse.isSparse) {
    const auto& sp = acc.sparse;
    if (sp.count < 0 || static_cast<std::size_t>(sp.count) > l.count)
      fail(name + " has " + std::to_string(sp.count) + " sparse elements but only " + std::to_string(l.count) +
           " elements");
    if (sp.indices.byteOffset < 0 || sp.values.byteOffset < 0) fail(name + " has a negative sparse byte offset");
    const int ict = sp.indices.componentType;
    const std::size_t is = static_cast<std::size_t>(componentSize(ict));
    if (ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
      fail(name + " has sparse indices of an invalid component type");
    const std::vector<std::uint8_t> idx = viewBytes(sp.indices.bufferView, name + " sparse indices");
    const std::vector<std::uint8_t> val = viewBytes(sp.values.bufferView, name + " sparse values");
    const std::size_t n = static_cast<std::size_t>(sp.count);
    const std::size_t elementSize = cs * static_cast<std::size_t>(components);
    if (static_cast<std::size_t>(sp.indices.byteOffset) + n * is > idx.size() ||
        static_cast<std::size_t>(sp.values.byteOffset) + n * elementSize > val.size())
      fail(name + " sparse data runs past the end of its buffer views");
    for (std::size_t k = 0; k < n; ++k) {
      const std::uint32_t target = decodeIndex(idx.data() + sp.indices.byteOffset + k * is, ict);
      if (target >= l.count) fail(name + " has sparse index " + std::to_string(target) + " out of range");
      for (std::size_t c = 0; c < static_cast<std::size_t>(components); ++c)
        out[target * static_cast<std::size_t>(components) + c] =
            decodeFloat(val.data() + sp.values.byteOffset + k * elementSize + c * cs, l.componentType, l.normalized);
    }
  }
  for (std::size_t i = 0; i < out.size(); ++i)
    if (!std::isfinite(out[i]))
      fail(name + " element " + std::to_string(i / static_cast<std::size_t>(components)) +
           " is not finite (NaN or infinity)");
  return out;
}

std::vector<std::uint32_t> AccessorReader::indices(int index, const std::string& what) const {
  const tinygltf::Accessor& acc = accessor(index, what);
  const std::string name = "accessor " + std::to_string(index) + " (" + what + ")";
  auto failFn = [&](const std::string& r) { fail(r + " (" + what + ")"); };
  const Layout l = layoutOf(model_, acc, index, options_, failFn);
  if (l.components != 1) fail(name + " must be SCALAR");
  if (l.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
      l.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      l.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    fail(name + " must hold unsigned 8, 16 or 32-bit integers");
  if (acc.sparse.isSparse) fail(name + ": sparse index accessors are not supported");
  if (!l.base) fail(name + " has no buffer view");
  std::vector<std::uint32_t> out(l.count);
  for (std::size_t i = 0; i < l.count; ++i) out[i] = decodeIndex(l.base + i * l.stride, l.componentType);
  return out;
}

float normalizedInteger(float value, int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return value / 255.0f;
    case TINYGLTF_COMPONENT_TYPE_BYTE:
      return std::max(value / 127.0f, -1.0f);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return value / 65535.0f;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
      return std::max(value / 32767.0f, -1.0f);
    default:
      return value;
  }
}

}  // namespace tsr::sg::gltf
