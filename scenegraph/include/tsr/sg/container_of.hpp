#pragma once
// Implements Container's reflection for a concrete type from its static
// fieldSpecs() tuple, and gives its setters one checked way to assign.
#include <algorithm>
#include <cassert>
#include <cmath>
#include <span>
#include <tuple>
#include <utility>
#include <vector>

#include "tsr/sg/coordinate_limit.hpp"
#include "tsr/sg/errors.hpp"
#include "tsr/sg/wire/field_spec.hpp"

namespace tsr::sg {

namespace detail {
// Plain values (colours, angles, planes) must be finite; matrices and
// vertex arrays place what back-ends trace, so they obey kMaxCoordinate too.
inline bool acceptable(float v) { return std::isfinite(v); }
template <int N>
bool acceptable(const glm::vec<N, float>& v) {
  for (int i = 0; i < N; ++i)
    if (!std::isfinite(v[i])) return false;
  return true;
}
template <int N>
bool traceable(const glm::vec<N, float>& v) {
  for (int i = 0; i < N; ++i)
    if (!withinCoordinateLimit(v[i])) return false;
  return true;
}
inline bool acceptable(const Mat4& m) {
  for (int c = 0; c < 4; ++c)
    if (!traceable(m[c])) return false;
  return true;
}
template <class T>
bool acceptable(const T&) {
  return true;
}
template <class E>
bool acceptableElements(std::span<const E> v) {
  if constexpr (requires(const E& e) { traceable(e); }) {
    return std::all_of(v.begin(), v.end(), [](const E& e) { return traceable(e); });
  } else {
    return true;
  }
}
template <class E>
bool acceptable(const std::vector<E>& v) {
  return acceptableElements(std::span<const E>(v));
}
template <class E>
bool acceptable(const SharedArray<E>& v) {
  return acceptableElements(std::span<const E>(v.get()));
}
template <class E>
bool acceptableElement(const E& e) {
  if constexpr (requires { traceable(e); })
    return traceable(e);
  else
    return true;
}

inline std::span<const ContainerId> idsOf(const ContainerId& id) {
  return id == kNoContainer ? std::span<const ContainerId>{} : std::span<const ContainerId>(&id, 1);
}
inline std::span<const ContainerId> idsOf(const std::vector<ContainerId>& ids) { return ids; }
}  // namespace detail

template <class Derived, ContainerType Type>
class ContainerOf : public Container {
 public:
  static constexpr ContainerType kType = Type;

  FieldIndex fieldCount() const override { return static_cast<FieldIndex>(kFirstOwnField + ownFieldCount()); }

  FieldInfo fieldInfo(FieldIndex f) const override {
    if (f == kName) return {"name", FieldKind::Value, 0};
    if (f == kAttachments) return {"attachments", FieldKind::Value, 0};
    FieldInfo info;
    withSpec(f, [&](const auto& spec) { info = {spec.name, spec.kind, spec.allowedTargets}; });
    return info;
  }

  void writeField(FieldIndex f, ByteWriter& w, const std::vector<ArrayRange>* edited) const override {
    if (f < kFirstOwnField) return writeBaseField(f, w);
    withSpec(f, [&](const auto& spec) {
      const auto& value = self().*spec.member;
      if constexpr (requires { codec::writeArray(w, value, edited); }) {
        codec::writeArray(w, value, spec.kind == FieldKind::Array ? edited : nullptr);
      } else {
        codec::write(w, value);
      }
    });
  }

  void readField(FieldIndex f, ByteReader& r, FieldReadContext& ctx) override {
    if (f < kFirstOwnField) return readBaseField(f, r, ctx);
    withSpec(f, [&](const auto& spec) {
      auto& value = self().*spec.member;
      if constexpr (requires { codec::readArray(r, value, ctx); }) {
        codec::readArray(r, value, ctx);
      } else {
        codec::read(r, value, ctx);
      }
    });
  }

  void forEachReference(FieldIndex f, const std::function<void(ContainerId)>& fn) const override {
    if (f < kFirstOwnField) return;
    withSpec(f, [&](const auto& spec) {
      if constexpr (requires { detail::idsOf(self().*spec.member); }) {
        if (spec.kind == FieldKind::Reference)
          for (ContainerId id : detail::idsOf(self().*spec.member)) fn(id);
      }
    });
  }

  std::size_t arrayLength(FieldIndex f) const override {
    std::size_t n = 0;
    if (f < kFirstOwnField) return 0;
    withSpec(f, [&](const auto& spec) {
      if constexpr (requires { (self().*spec.member).size(); }) {
        if (spec.kind == FieldKind::Array) n = (self().*spec.member).size();
      }
    });
    return n;
  }

 protected:
  ContainerOf() : Container(Type) {}

  // The number of the field that `Member` holds, from fieldSpecs().
  template <auto Member>
  static constexpr FieldIndex fieldOf() {
    constexpr auto specs = Derived::fieldSpecs();
    FieldIndex found = kMaxFields;
    std::apply(
        [&](const auto&... spec) {
          (
              [&] {
                if constexpr (std::is_same_v<decltype(spec.member), decltype(Member)>)
                  if (spec.member == Member) found = spec.number;
              }(),
              ...);
        },
        specs);
    return found;
  }

  // Sets the field that `Member` holds: the one way setters change a field,
  // so the number they mark is the one the codec writes.
  template <auto Member, class V>
  void set(V&& value) {
    constexpr FieldIndex f = fieldOf<Member>();
    static_assert(f < kMaxFields, "the member is not declared in fieldSpecs()");
    auto& member = self().*Member;
    using T = std::decay_t<decltype(member)>;
    if constexpr (kindOf(f) == FieldKind::Reference)
      assignReference(f, member, T(std::forward<V>(value)));
    else
      assign(f, member, T(std::forward<V>(value)));
  }

  // Overwrites elements [begin, begin + values.size()) of the array field
  // that `Member` holds.
  template <auto Member, class E>
  void setElements(std::size_t begin, std::span<const E> values) {
    constexpr FieldIndex f = fieldOf<Member>();
    static_assert(f < kMaxFields && kindOf(f) == FieldKind::Array, "not an array field of fieldSpecs()");
    assignRange(f, self().*Member, begin, values);
  }

  void dropReference(FieldIndex f, ContainerId target) override {
    withSpec(f, [&](const auto& spec) {
      auto& value = self().*spec.member;
      using T = std::decay_t<decltype(value)>;
      if constexpr (std::is_same_v<T, ContainerId>) {
        if (spec.kind == FieldKind::Reference && value == target) assignReference(f, value, kNoContainer);
      } else if constexpr (std::is_same_v<T, std::vector<ContainerId>>) {
        if (spec.kind == FieldKind::Reference) {
          T kept;
          std::copy_if(value.begin(), value.end(), std::back_inserter(kept),
                       [&](ContainerId c) { return c != target; });
          if (kept.size() != value.size()) assignReference(f, value, std::move(kept));
        }
      }
    });
  }

 private:
  // Assigns a plain or array value, rejecting non-finite floats and
  // coordinates beyond kMaxCoordinate.
  template <class T>
  void assign(FieldIndex f, T& member, T value) {
    if (!detail::acceptable(value)) throw SceneError(invalidValue(f));
    member = std::move(value);
    touch(f);
  }

  // Assigns a reference field after checking what it will name.
  template <class T>
  void assignReference(FieldIndex f, T& member, T value) {
    checkReferences(f, detail::idsOf(value));
    unlinkReferences(f, detail::idsOf(member));
    member = std::move(value);
    linkReferences(f, detail::idsOf(member));
    touch(f);
  }

  // Overwrites elements [begin, begin + values.size()) of an array field.
  template <class E>
  void assignRange(FieldIndex f, std::vector<E>& member, std::size_t begin, std::span<const E> values) {
    checkRange(f, member.size(), begin, values);
    std::copy(values.begin(), values.end(), member.begin() + static_cast<std::ptrdiff_t>(begin));
    touchRange(f, begin, begin + values.size());
  }
  template <class E>
  void assignRange(FieldIndex f, SharedArray<E>& member, std::size_t begin, std::span<const E> values) {
    checkRange(f, member.size(), begin, values);
    if (values.empty()) return touchRange(f, begin, begin);
    // A copy when a list or replica holds them, or they are another owner's memory (a mapped entry).
    const std::span<E> elements = member.writable();
    std::copy(values.begin(), values.end(), elements.begin() + static_cast<std::ptrdiff_t>(begin));
    touchRange(f, begin, begin + values.size());
  }
  template <class E>
  void checkRange(FieldIndex f, std::size_t size, std::size_t begin, std::span<const E> values) const {
    if (begin > size || values.size() > size - begin)
      throw SceneError(std::string(typeName(Type)) + "." + std::string(fieldInfo(f).name) + ": range [" +
                       std::to_string(begin) + ", +" + std::to_string(values.size()) + ") outside " +
                       std::to_string(size) + " elements");
    for (const E& v : values)
      if (!detail::acceptableElement(v)) throw SceneError(invalidValue(f));
  }

  // A function, not a constant, because Derived is incomplete while this
  // base is instantiated.
  static constexpr std::size_t ownFieldCount() {
    constexpr std::size_t n = std::tuple_size_v<decltype(Derived::fieldSpecs())>;
    static_assert(kFirstOwnField + n <= kMaxFields);
    static_assert(numberedInOrder(), "fieldSpecs() must list the fields in number order from kFirstOwnField");
    return n;
  }

  // The wire uses positions, setters use numbers: they must agree.
  static constexpr bool numberedInOrder() {
    constexpr auto specs = Derived::fieldSpecs();
    return [&]<std::size_t... I>(std::index_sequence<I...>) {
      return ((std::get<I>(specs).number == kFirstOwnField + I) && ...);
    }
    (std::make_index_sequence<std::tuple_size_v<decltype(specs)>>{});
  }

  static constexpr FieldKind kindOf(FieldIndex f) {
    FieldKind kind = FieldKind::Value;
    std::apply([&](const auto&... spec) { ((spec.number == f ? (kind = spec.kind, 0) : 0), ...); },
               Derived::fieldSpecs());
    return kind;
  }

  std::string invalidValue(FieldIndex f) const {
    return std::string(typeName(Type)) + "." + std::string(fieldInfo(f).name) +
           ": non-finite value or a coordinate beyond 1e12 (sg::kMaxCoordinate)";
  }

  Derived& self() { return static_cast<Derived&>(*this); }
  const Derived& self() const { return static_cast<const Derived&>(*this); }

  template <class Fn>
  static void withSpec(FieldIndex f, Fn&& fn) {
    static constexpr auto specs = Derived::fieldSpecs();
    [&]<std::size_t... I>(std::index_sequence<I...>) {
      [[maybe_unused]] bool found = ((f == kFirstOwnField + I ? (fn(std::get<I>(specs)), true) : false) || ...);
      assert(found && "field index out of range");
    }
    (std::make_index_sequence<ownFieldCount()>{});
  }
};

}  // namespace tsr::sg
