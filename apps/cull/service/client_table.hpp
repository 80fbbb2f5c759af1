#pragma once
// Who holds what of the service, per client address: connections, cull
// requests in flight, preview streams. A slot is taken before the work
// starts and given back when its holder goes (ClientSlot, RAII), so a
// client that vanishes mid-request frees its share with it.
#include <array>
#include <mutex>
#include <string>
#include <unordered_map>

#include <boost/asio/ip/address.hpp>

namespace tsr::app {

enum class SlotKind { Connection, Request, Preview };

class ClientTable;

class ClientSlot {
 public:
  ClientSlot() = default;
  ClientSlot(ClientTable* table, const boost::asio::ip::address& address, SlotKind kind)
      : table_(table), address_(address), kind_(kind) {}
  ClientSlot(ClientSlot&& other) noexcept { *this = std::move(other); }
  ClientSlot& operator=(ClientSlot&& other) noexcept;
  ~ClientSlot() { release(); }
  explicit operator bool() const { return table_ != nullptr; }
  void release();

 private:
  ClientTable* table_ = nullptr;
  boost::asio::ip::address address_;
  SlotKind kind_ = SlotKind::Connection;
};

class ClientTable {
 public:
  // The most one address may hold of each kind, and of connections in all.
  ClientTable(int connectionsPerAddress, int requestsPerAddress, int previewsPerAddress, int totalConnections)
      : perAddress_{connectionsPerAddress, requestsPerAddress, previewsPerAddress},
        totalConnections_(totalConnections) {}

  enum class Refusal { None, Address, Service };
  // A slot, or why not: the address holds its share (429) or the service
  // is full (503, connections only).
  Refusal take(const boost::asio::ip::address& address, SlotKind kind, ClientSlot& slot);
  int connections() const;
  int held(SlotKind kind) const;  // by everyone
  std::size_t addresses() const;

 private:
  friend class ClientSlot;
  void give(const boost::asio::ip::address& address, SlotKind kind);

  using Counts = std::array<int, 3>;
  const Counts perAddress_;
  const int totalConnections_;
  mutable std::mutex mutex_;
  std::unordered_map<std::string, Counts> byAddress_;  // only addresses holding something
  Counts total_{};
};

}  // namespace tsr::app
