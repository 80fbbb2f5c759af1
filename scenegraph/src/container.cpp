#include "tsr/sg/container.hpp"

#include <algorithm>
#include <cmath>

#include "tsr/sg/scene.hpp"

namespace tsr::sg {

void Container::setName(std::string name) {
  name_ = std::move(name);
  touch(kName);
}

const AttachmentValue* Container::attachment(std::string_view key) const {
  auto it = attachments_.find(key);
  return it == attachments_.end() ? nullptr : &it->second;
}

void Container::setAttachment(std::string key, AttachmentValue value) {
  if (key.empty()) throw SceneError("attachment names must not be empty");
  if (const auto* d = std::get_if<double>(&value); d && !std::isfinite(*d))
    throw SceneError("attachment " + key + ": non-finite value");
  if (const auto* v = std::get_if<std::vector<float>>(&value);
      v && !std::all_of(v->begin(), v->end(), [](float f) { return std::isfinite(f); }))
    throw SceneError("attachment " + key + ": non-finite value");
  attachments_.insert_or_assign(std::move(key), std::move(value));
  touch(kAttachments);
}

void Container::removeAttachment(std::string_view key) {
  auto it = attachments_.find(key);
  if (it == attachments_.end()) return;
  attachments_.erase(it);
  touch(kAttachments);
}

FieldMask Container::referenceFields() const {
  FieldMask mask = 0;
  for (FieldIndex f = kFirstOwnField; f < fieldCount(); ++f)
    if (fieldInfo(f).kind == FieldKind::Reference) mask |= fieldBit(f);
  return mask;
}

void Container::touch(FieldIndex f) {
  if (scene_) scene_->recordChange(*this, f);
}

void Container::touchRange(FieldIndex f, std::uint64_t begin, std::uint64_t end) {
  if (scene_) scene_->recordRange(*this, f, begin, end);
}

void Container::checkReferences(FieldIndex f, std::span<const ContainerId> added) const {
  if (scene_) scene_->checkReferences(*this, f, added);
}

void Container::linkReferences(FieldIndex f, std::span<const ContainerId> ids) {
  if (!scene_) return;
  for (ContainerId id : ids) scene_->link(id_, f, id);
}

void Container::unlinkReferences(FieldIndex f, std::span<const ContainerId> ids) {
  if (!scene_) return;
  for (ContainerId id : ids) scene_->unlink(id_, f, id);
}

void Container::writeBaseField(FieldIndex f, ByteWriter& w) const {
  if (f == kName)
    codec::write(w, name_);
  else
    codec::write(w, attachments_);
}

void Container::readBaseField(FieldIndex f, ByteReader& r, FieldReadContext& ctx) {
  if (f == kName)
    codec::read(r, name_, ctx);
  else
    codec::read(r, attachments_, ctx);
}

}  // namespace tsr::sg
