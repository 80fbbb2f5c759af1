// Thread multi-buffering: one thread edits and commits frame n+1 while
// another applies frame n to its own replica and reads it. The only shared
// things are immutable change lists and the queue that hands them over.
#include <gtest/gtest.h>

#include <condition_variable>
#include <deque>
#include <mutex>
#include <thread>

#include "random_edits.hpp"
#include "tsr/sg/changes/change_log.hpp"
#include "tsr/sg/scene.hpp"

using namespace tsr::sg;

namespace {
class ListQueue {
 public:
  void push(ChangeListPtr list) {
    {
      std::lock_guard lock(mutex_);
      lists_.push_back(std::move(list));
    }
    ready_.notify_one();
  }
  ChangeListPtr pop() {  // null: the producer is done
    std::unique_lock lock(mutex_);
    ready_.wait(lock, [&] { return !lists_.empty(); });
    auto list = std::move(lists_.front());
    lists_.pop_front();
    return list;
  }

 private:
  std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<ChangeListPtr> lists_;
};
}  // namespace

TEST(ConcurrentReplica, EditingAndApplyingRunTogether) {
  constexpr int kFrames = 300;
  Scene source;
  ListQueue queue;
  ChangeLog log(16);
  std::vector<std::uint64_t> sourceHashes(kFrames + 1);
  std::vector<std::uint64_t> replicaHashes(kFrames + 1);

  std::thread renderThread([&] {
    Scene replica;
    std::size_t trianglesSeen = 0;
    while (auto list = queue.pop()) {
      replica.apply(*list);
      // Read the replica as a renderer would while the editor moves on.
      for (ContainerId id : replica.ids())
        if (auto* g = replica.find<Geometry>(id)) trianglesSeen += g->triangleCount();
      // A second consumer catching up through the log from another thread.
      (void)log.since(replica.version() > 3 ? replica.version() - 3 : 0);
      replicaHashes[replica.version()] = replica.contentHash();
    }
    EXPECT_GT(trianglesSeen, 0u);
  });

  test::RandomEditor edit(source, 42);
  for (int frame = 1; frame <= kFrames; ++frame) {
    for (int i = 0; i < 10; ++i) edit.editOne();
    auto list = source.commit();
    sourceHashes[source.version()] = source.contentHash();
    log.append(list);
    queue.push(std::move(list));
  }
  queue.push(nullptr);
  renderThread.join();
  for (int v = 1; v <= kFrames; ++v) ASSERT_EQ(replicaHashes[v], sourceHashes[v]) << "version " << v;
}
