#pragma once
// The base of every scene graph container: a stable id, a name, attachments,
// and field reflection that the change list, the codec and the hash use.
#include <functional>
#include <span>
#include <string>

#include "tsr/sg/attachment.hpp"
#include "tsr/sg/types.hpp"
#include "tsr/sg/wire/field_codec.hpp"

namespace tsr::sg {

class Scene;

// Value: plain data. Reference: ids of other containers (validated, indexed
// so destruction can detach them). Array: element arrays editable by range.
enum class FieldKind : std::uint8_t { Value, Reference, Array };

struct FieldInfo {
  std::string_view name;
  FieldKind kind = FieldKind::Value;
  TypeSet allowedTargets = 0;  // for references: the container types they may name
};

class Container {
 public:
  static constexpr FieldIndex kName = 0;
  static constexpr FieldIndex kAttachments = 1;
  static constexpr FieldIndex kFirstOwnField = 2;

  virtual ~Container() = default;
  Container(const Container&) = delete;
  Container& operator=(const Container&) = delete;

  ContainerId id() const { return id_; }
  ContainerType type() const { return type_; }
  Scene* scene() const { return scene_; }

  const std::string& name() const { return name_; }
  void setName(std::string name);

  const Attachments& attachments() const { return attachments_; }
  const AttachmentValue* attachment(std::string_view key) const;
  void setAttachment(std::string key, AttachmentValue value);
  void removeAttachment(std::string_view key);

  // Reflection over the fields of the concrete type.
  virtual FieldIndex fieldCount() const = 0;
  virtual FieldInfo fieldInfo(FieldIndex f) const = 0;
  FieldMask allFields() const { return fieldCount() == 64 ? ~FieldMask{0} : (FieldMask{1} << fieldCount()) - 1; }
  FieldMask referenceFields() const;

  // Serialises field f; with `edited`, only those element ranges of an array.
  virtual void writeField(FieldIndex f, ByteWriter& w, const std::vector<ArrayRange>* edited) const = 0;
  // Reads field f from bytes written by writeField; throws DecodeError.
  virtual void readField(FieldIndex f, ByteReader& r, FieldReadContext& ctx) = 0;
  // The ids a reference field names (no zeros).
  virtual void forEachReference(FieldIndex f, const std::function<void(ContainerId)>& fn) const = 0;
  // Length of an array field (0 for other fields).
  virtual std::size_t arrayLength(FieldIndex f) const = 0;

 protected:
  explicit Container(ContainerType type) : type_(type) {}

  // Records that field f changed this frame.
  void touch(FieldIndex f);
  // Records that elements [begin, end) of array field f changed this frame.
  void touchRange(FieldIndex f, std::uint64_t begin, std::uint64_t end);
  // Checks ids about to be added to reference field f: they must exist in
  // this scene, be of an allowed type and, for children, make no cycle.
  void checkReferences(FieldIndex f, std::span<const ContainerId> added) const;
  // Keeps the scene's index of who refers to whom in step with field f.
  void linkReferences(FieldIndex f, std::span<const ContainerId> ids);
  void unlinkReferences(FieldIndex f, std::span<const ContainerId> ids);
  // Removes `target` from reference field f (a child entry, or a single id
  // reset to none), as when the target is destroyed.
  virtual void dropReference(FieldIndex f, ContainerId target) = 0;

 private:
  friend class Scene;
  friend class ChangeApplier;
  void writeBaseField(FieldIndex f, ByteWriter& w) const;
  void readBaseField(FieldIndex f, ByteReader& r, FieldReadContext& ctx);

  template <class, ContainerType>
  friend class ContainerOf;

  ContainerId id_ = kNoContainer;
  ContainerType type_;
  Scene* scene_ = nullptr;
  std::string name_;
  Attachments attachments_;
};

}  // namespace tsr::sg
