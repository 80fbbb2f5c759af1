#pragma once
// What a node link reports to the client thread, and the queue it goes
// through. The client thread waits on the inbox with a deadline, never on
// a socket, so one dead node cannot hold up the rest.
#include <chrono>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <optional>
#include <string>

#include "tsr/cluster/messages.hpp"

namespace tsr::cluster {

struct LinkEvent {
  enum class Kind { Connected, Failed, Closed, Received };
  Kind kind = Kind::Received;
  std::size_t node = 0;
  std::uint64_t generation = 0;  // which connection attempt; stale ones are ignored
  Message message;
  Welcome welcome;
  std::string reason;
};

class Inbox {
 public:
  void push(LinkEvent e) {
    {
      std::lock_guard lock(mutex_);
      events_.push_back(std::move(e));
    }
    wake_.notify_one();
  }
  // The next event, or nothing once `deadline` passed.
  std::optional<LinkEvent> pop(std::chrono::steady_clock::time_point deadline) {
    std::unique_lock lock(mutex_);
    if (!wake_.wait_until(lock, deadline, [&] { return !events_.empty(); })) return std::nullopt;
    LinkEvent e = std::move(events_.front());
    events_.pop_front();
    return e;
  }

 private:
  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<LinkEvent> events_;
};

}  // namespace tsr::cluster
