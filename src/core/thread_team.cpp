#include "core/thread_team.hpp"

#include <algorithm>
#include <chrono>

namespace vdec {

namespace {

// How long an idle worker polls for the next loop before it sleeps. The gaps between a step's
// loops (the serial stages, the step's bookkeeping) last microseconds; waking a sleeping thread
// takes tens of them on a virtual machine, more than a loop of ten thousand zones saves. Polling
// gives the core away at every poll (yield), so a job waiting for the core gets it.
constexpr auto kPollBeforeSleeping = std::chrono::microseconds(200);

// A share word: generation (20 bits), front and back (22 bits each: up to 4 million chunks).
constexpr int kIndexBits = 22;
constexpr std::uint64_t kIndexMask = (std::uint64_t{1} << kIndexBits) - 1;
constexpr std::uint32_t kGenerationMask = (1u << 20) - 1;

std::uint64_t pack(std::uint32_t generation, std::uint64_t front, std::uint64_t back) {
  return (std::uint64_t{generation & kGenerationMask} << (2 * kIndexBits)) | (front << kIndexBits) | back;
}
std::uint32_t generationOf(std::uint64_t share) { return static_cast<std::uint32_t>(share >> (2 * kIndexBits)); }
int frontOf(std::uint64_t share) { return static_cast<int>((share >> kIndexBits) & kIndexMask); }
int backOf(std::uint64_t share) { return static_cast<int>(share & kIndexMask); }

}  // namespace

ThreadTeam& ThreadTeam::instance() {
  static ThreadTeam team;
  return team;
}

ThreadTeam::~ThreadTeam() { setThreadCount(1); }

void ThreadTeam::setThreadCount(int count) {
  const std::size_t wanted = count > 1 ? static_cast<std::size_t>(count - 1) : 0;
  if (wanted == workers_.size()) return;
  if (!workers_.empty()) {
    stopping_.store(true, std::memory_order_release);
    generation_.fetch_add(1, std::memory_order_release);
    generation_.notify_all();
    for (std::thread& t : workers_) t.join();
    workers_.clear();
    stopping_.store(false, std::memory_order_release);
  }
  shares_ = std::make_unique<std::atomic<std::uint64_t>[]>(wanted + 1);
  for (std::size_t i = 0; i <= wanted; ++i) shares_[i].store(0, std::memory_order_relaxed);
  // The generation the workers start from is read here: one that started late would otherwise
  // take a loop published meanwhile for one it had seen.
  const std::uint32_t current = generation_.load(std::memory_order_acquire);
  for (std::size_t i = 0; i < wanted; ++i)
    workers_.emplace_back([this, i, current] { work(static_cast<int>(i) + 1, current); });
}

void ThreadTeam::run(int chunks, Body body, void* context) {
  if (workers_.empty() || chunks <= 1) {
    for (int c = 0; c < chunks; ++c) body(context, c);
    return;
  }
  Timing* timing = nullptr;
  for (Timing& t : timings_)
    if (t.body == body) timing = &t;
  if (timing == nullptr) timing = &timings_.emplace_back(Timing{body});
  ++timing->loops;
  const bool probe = timing->loops % kProbeEvery == 0;
  // The first shared loop wakes the workers and fills their caches: it is not counted.
  const bool warmUp = timing->loops == 1;
  const bool shareIt = timing->shared == 0.0   ? true
                       : timing->alone == 0.0  ? false
                                               : (timing->shared < timing->alone) != probe;
  // A running mean over about eight loops, which follows a change of load within a few steps; a
  // probe, rare, counts for half. A single loop counts for at most 1.5 times the mean: a thread
  // held up once (an interrupt, the hypervisor) says nothing of the next loops.
  auto remember = [chunks, probe](double& mean, std::chrono::steady_clock::time_point since) {
    const double perChunk = std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count() / chunks;
    mean = mean == 0.0 ? perChunk : mean + (probe ? 0.5 : 0.125) * (std::min(perChunk, 1.5 * mean) - mean);
  };
  workersIdle_.store(!shareIt && !probe, std::memory_order_relaxed);
  const auto start = std::chrono::steady_clock::now();
  if (!shareIt) {
    for (int c = 0; c < chunks; ++c) body(context, c);
    remember(timing->alone, start);
    return;
  }
  const std::uint32_t generation = (generation_.load(std::memory_order_relaxed) + 1) & kGenerationMask;
  Loop& loop = loops_[generation & 1];
  loop.body.store(body, std::memory_order_relaxed);
  loop.context.store(context, std::memory_order_relaxed);
  loop.done.store(0, std::memory_order_relaxed);
  const int threads = threadCount();
  for (int t = 0; t < threads; ++t) {
    const std::uint64_t front = static_cast<std::uint64_t>(chunks) * t / threads;
    const std::uint64_t back = static_cast<std::uint64_t>(chunks) * (t + 1) / threads;
    shares_[t].store(pack(generation, front, back), std::memory_order_relaxed);
  }
  generation_.store(generation, std::memory_order_release);
  generation_.notify_all();
  takeChunks(0, generation);
  // Only chunks another thread has taken are waited for; each is a few microseconds of work.
  while (loop.done.load(std::memory_order_acquire) < chunks) std::this_thread::yield();
  if (!warmUp) remember(timing->shared, start);
}

void ThreadTeam::takeChunks(int self, std::uint32_t generation) {
  Loop& loop = loops_[generation & 1];
  const int threads = threadCount();
  for (int k = 0; k < threads; ++k) {
    const int owner = (self + k) % threads;
    std::atomic<std::uint64_t>& share = shares_[owner];
    std::uint64_t word = share.load(std::memory_order_acquire);
    for (;;) {
      if (generationOf(word) != generation) return;  // the loop is over
      const int front = frontOf(word), back = backOf(word);
      if (front >= back) break;
      // Its own share from the front, another's from the back: the two meet in the middle.
      const bool own = owner == self;
      const std::uint64_t taken = own ? pack(generation, front + 1, back) : pack(generation, front, back - 1);
      if (!share.compare_exchange_weak(word, taken, std::memory_order_acq_rel, std::memory_order_acquire)) continue;
      // The chunk is ours and the loop not yet done, so its slot still holds it.
      loop.body.load(std::memory_order_relaxed)(loop.context.load(std::memory_order_relaxed), own ? front : back - 1);
      loop.done.fetch_add(1, std::memory_order_release);
      word = share.load(std::memory_order_acquire);
    }
  }
}

void ThreadTeam::work(int self, std::uint32_t seen) {
  for (;;) {
    const auto idleSince = std::chrono::steady_clock::now();
    std::uint32_t generation = generation_.load(std::memory_order_acquire);
    while (generation == seen) {
      if (!workersIdle_.load(std::memory_order_relaxed) &&
          std::chrono::steady_clock::now() - idleSince < kPollBeforeSleeping) {
        std::this_thread::yield();
      } else {
        generation_.wait(seen, std::memory_order_acquire);
      }
      generation = generation_.load(std::memory_order_acquire);
    }
    if (stopping_.load(std::memory_order_acquire)) return;
    seen = generation;
    takeChunks(self, generation);
  }
}

}  // namespace vdec
