#pragma once
// Compile-time description of one field: its name, kind and the member that
// holds it. A container type lists its fields as a tuple of these; the
// position in the tuple is the field's wire number.
#include <string_view>

#include "tsr/sg/container.hpp"

namespace tsr::sg {

template <class Owner, class T>
struct FieldSpec {
  std::string_view name;
  T Owner::*member;
  FieldKind kind;
  TypeSet allowedTargets;
};

template <class Owner, class T>
constexpr FieldSpec<Owner, T> valueField(std::string_view name, T Owner::*member) {
  return {name, member, FieldKind::Value, 0};
}
template <class Owner, class T>
constexpr FieldSpec<Owner, T> arrayField(std::string_view name, T Owner::*member) {
  return {name, member, FieldKind::Array, 0};
}
template <class Owner, class T>
constexpr FieldSpec<Owner, T> referenceField(std::string_view name, T Owner::*member, TypeSet allowed) {
  return {name, member, FieldKind::Reference, allowed};
}

}  // namespace tsr::sg
