#include "service/client_table.hpp"

#include <utility>

namespace tsr::app {

ClientSlot& ClientSlot::operator=(ClientSlot&& other) noexcept {
  if (this != &other) {
    release();
    table_ = std::exchange(other.table_, nullptr);
    address_ = other.address_;
    kind_ = other.kind_;
  }
  return *this;
}

void ClientSlot::release() {
  if (table_) std::exchange(table_, nullptr)->give(address_, kind_);
}

ClientTable::Refusal ClientTable::take(const boost::asio::ip::address& address, SlotKind kind, ClientSlot& slot) {
  const auto k = std::size_t(kind);
  std::lock_guard lock(mutex_);
  if (kind == SlotKind::Connection && total_[k] >= totalConnections_) return Refusal::Service;
  Counts& counts = byAddress_[address.to_string()];
  if (counts[k] >= perAddress_[k]) {
    if (counts == Counts{}) byAddress_.erase(address.to_string());
    return Refusal::Address;
  }
  ++counts[k];
  ++total_[k];
  slot = ClientSlot(this, address, kind);
  return Refusal::None;
}

void ClientTable::give(const boost::asio::ip::address& address, SlotKind kind) {
  const auto k = std::size_t(kind);
  std::lock_guard lock(mutex_);
  auto it = byAddress_.find(address.to_string());
  if (it == byAddress_.end()) return;
  --it->second[k];
  --total_[k];
  if (it->second == Counts{}) byAddress_.erase(it);
}

int ClientTable::connections() const { return held(SlotKind::Connection); }

int ClientTable::held(SlotKind kind) const {
  std::lock_guard lock(mutex_);
  return total_[std::size_t(kind)];
}

std::size_t ClientTable::addresses() const {
  std::lock_guard lock(mutex_);
  return byAddress_.size();
}

}  // namespace tsr::app
