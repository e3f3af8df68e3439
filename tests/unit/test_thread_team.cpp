#include <gtest/gtest.h>

#include <atomic>
#include <set>
#include <thread>
#include <vector>

#include "core/parallel.hpp"
#include "core/thread_team.hpp"
#include "requirements.hpp"

using namespace vdec;

namespace {

struct Counts {
  std::vector<std::atomic<int>> runs;
  explicit Counts(int n) : runs(static_cast<std::size_t>(n)) {}
};

}  // namespace

TEST(ThreadTeam, EveryChunkOfEveryLoopRunsExactlyOnceAtAnyThreadCount) {
  VDEC_REQUIREMENTS("REQ-RUN-010");
  for (int threads : {1, 2, 3, 4}) {
    ThreadTeam::instance().setThreadCount(threads);
    EXPECT_EQ(ThreadTeam::instance().threadCount(), threads);
    // Many short loops back to back: a worker late for one loop must not run chunks of the next
    // with the old loop's body, nor count them for it.
    for (int loop = 0; loop < 2000; ++loop) {
      const int chunks = 1 + loop % 37;
      Counts counts(chunks);
      ThreadTeam::instance().run(chunks, [](void* context, int c) {
        static_cast<Counts*>(context)->runs[static_cast<std::size_t>(c)].fetch_add(1);
      }, &counts);
      for (int c = 0; c < chunks; ++c) ASSERT_EQ(counts.runs[static_cast<std::size_t>(c)].load(), 1) << threads << " threads, loop " << loop;
    }
  }
  ThreadTeam::instance().setThreadCount(1);
}

TEST(ThreadTeam, WorkersShareALoopsChunks) {
  VDEC_REQUIREMENTS("REQ-RUN-010");
  ThreadTeam::instance().setThreadCount(2);
  struct Seen {
    std::atomic<int> spins{0};
    std::vector<std::thread::id> ids = std::vector<std::thread::id>(64);
  } seen;
  // Chunks long enough (about a millisecond each) for the worker to wake and take some.
  ThreadTeam::instance().run(64, [](void* context, int c) {
    Seen& s = *static_cast<Seen*>(context);
    const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(1);
    while (std::chrono::steady_clock::now() < until) s.spins.fetch_add(1, std::memory_order_relaxed);
    s.ids[static_cast<std::size_t>(c)] = std::this_thread::get_id();
  }, &seen);
  ThreadTeam::instance().setThreadCount(1);
  EXPECT_EQ(std::set<std::thread::id>(seen.ids.begin(), seen.ids.end()).size(), 2u);
}

TEST(ThreadTeam, ChunkedSumsAreBitwiseTheSameAtAnyThreadCount) {
  VDEC_REQUIREMENTS("REQ-RUN-010");
  // Terms of very different sizes: a different order of addition changes the sum's last bits.
  auto term = [](int i) { return (i % 3 == 0 ? 1e16 : 1.0) * (i % 2 ? 1.0 : -1.0) + 0.1 * i; };
  ThreadTeam::instance().setThreadCount(1);
  const double one = deterministicSum(100000, term);
  for (int threads : {2, 3, 4}) {
    ThreadTeam::instance().setThreadCount(threads);
    for (int repeat = 0; repeat < 20; ++repeat) EXPECT_EQ(deterministicSum(100000, term), one);
  }
  ThreadTeam::instance().setThreadCount(1);
}
