#pragma once
// /v1/cull requests from every connection, waiting for the ranking: at
// most `capacity` wait (a full queue refuses at once, 503), the oldest is
// ranked first, and one whose client went away is dropped unranked. The
// ranking runs on the queue's own worker, never on the network's threads;
// one worker, because every ranking renders the service's one converted
// scene (the coverage renderer spreads each render over --threads).
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "service/cull_service.hpp"

namespace tsr::app {

struct CullJob {
  using Clock = std::chrono::steady_clock;
  CullQuery query;
  // Called once on the worker: the answer, or the failure's message.
  std::function<void(const CullAnswer*, const std::string& error)> done;
  std::atomic<bool> gone{false};  // the client left: drop it (set from any thread)
  Clock::time_point queued{};
};

struct CullQueueStatus {
  std::size_t waiting = 0, capacity = 0;
  bool ranking = false;
  std::uint64_t answered = 0, dropped = 0, refused = 0;
  double oldestWaitMs = 0;     // of those waiting now
  double recentRankingMs = 0;  // a moving average of one ranking's time
};

class CullQueue {
 public:
  CullQueue(CullService& cull, std::size_t capacity);
  ~CullQueue();  // the worker stops; jobs still waiting are dropped unanswered
  CullQueue(const CullQueue&) = delete;
  CullQueue& operator=(const CullQueue&) = delete;

  // False when the queue is full (the job is not kept).
  bool push(std::shared_ptr<CullJob> job);
  CullQueueStatus status() const;

 private:
  void work();

  CullService& cull_;
  const std::size_t capacity_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::shared_ptr<CullJob>> waiting_;
  bool stopping_ = false, ranking_ = false;
  std::uint64_t answered_ = 0, dropped_ = 0, refused_ = 0;
  double recentMs_ = 0;
  std::thread worker_;
};

}  // namespace tsr::app
