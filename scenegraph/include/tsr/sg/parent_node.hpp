#pragma once
// A node with children (Group, Transform). Children are ids of nodes; a node
// may have several parents (instancing) but the graph must stay acyclic.
#include <algorithm>
#include <vector>

#include "tsr/sg/container_of.hpp"

namespace tsr::sg {

template <class Derived, ContainerType Type>
class ParentNode : public ContainerOf<Derived, Type> {
 public:
  static constexpr FieldIndex Children = Container::kFirstOwnField;

  const std::vector<ContainerId>& children() const { return children_; }
  void setChildren(std::vector<ContainerId> children) {
    this->template set<&ParentNode::children_>(std::move(children));
  }
  void addChild(ContainerId child) {
    std::span<const ContainerId> added(&child, 1);
    this->checkReferences(Children, added);
    children_.push_back(child);
    this->linkReferences(Children, added);
    this->touch(Children);
  }
  // Removes every occurrence of `child`.
  void removeChild(ContainerId child) { this->dropReference(Children, child); }

 protected:
  static constexpr auto childrenSpec() {
    return referenceField(Children, "children", &ParentNode::children_, kNodeTypes, &ParentNode::setChildren);
  }

 private:
  std::vector<ContainerId> children_;
};

class Group final : public ParentNode<Group, ContainerType::Group> {
 public:
  static constexpr auto fieldSpecs() { return std::tuple{childrenSpec()}; }
};

class Transform final : public ParentNode<Transform, ContainerType::Transform> {
 public:
  enum Field : FieldIndex { Matrix = Children + 1, FrameMotion };
  // The matrix at the frame's time.
  const Mat4& matrix() const { return matrix_; }
  void setMatrix(const Mat4& m) { set<&Transform::matrix_>(m); }
  // How the matrix changes over one frame interval, in the parent's space:
  // at the interval's end it is frameMotion() * matrix(). The identity (the
  // default) keeps the node still; a camera shutter that stays open over
  // part of the interval blurs what moves (Camera::shutterOpen()).
  const Mat4& frameMotion() const { return motion_; }
  void setFrameMotion(const Mat4& m) { set<&Transform::motion_>(m); }
  // The matrix at the end of the frame interval.
  Mat4 matrixAtEnd() const { return motion_ * matrix_; }

  static constexpr auto fieldSpecs() {
    return std::tuple{childrenSpec(), valueField(Matrix, "matrix", &Transform::matrix_, &Transform::setMatrix),
                      valueField(FrameMotion, "frameMotion", &Transform::motion_, &Transform::setFrameMotion)};
  }

 private:
  Mat4 matrix_{1.0f};
  Mat4 motion_{1.0f};
};

}  // namespace tsr::sg
