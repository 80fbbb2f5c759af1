#pragma once
// Compile-time description of one field: its number, wire name, kind, the
// member that holds it and the public setter that changes it. A container
// type declares its fields once, as a tuple of these in number order
// (ContainerOf checks the order); setters name the member and take the
// number from here, and the field tests call every setter from here.
#include <string_view>

#include "tsr/sg/container.hpp"

namespace tsr::sg {

template <class Owner, class T, class Setter>
struct FieldSpec {
  FieldIndex number;
  std::string_view name;
  T Owner::*member;
  FieldKind kind;
  TypeSet allowedTargets;
  // A member function taking the value, or a function (Owner&, value) for
  // a field changed only together with others (an image's layout).
  Setter setter;
};

template <class Owner, class T, class Setter>
constexpr FieldSpec<Owner, T, Setter> valueField(FieldIndex number, std::string_view name, T Owner::*member,
                                                 Setter setter) {
  return {number, name, member, FieldKind::Value, 0, setter};
}
template <class Owner, class T, class Setter>
constexpr FieldSpec<Owner, T, Setter> arrayField(FieldIndex number, std::string_view name, T Owner::*member,
                                                 Setter setter) {
  return {number, name, member, FieldKind::Array, 0, setter};
}
template <class Owner, class T, class Setter>
constexpr FieldSpec<Owner, T, Setter> referenceField(FieldIndex number, std::string_view name, T Owner::*member,
                                                     TypeSet allowed, Setter setter) {
  return {number, name, member, FieldKind::Reference, allowed, setter};
}

}  // namespace tsr::sg
