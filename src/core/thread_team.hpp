#pragma once
// The run's threads: the calling thread and count - 1 workers share a loop's chunks
// (docs/performance.md#threads). Each thread owns a contiguous share of the chunks and works
// through it from the front, so that a thread meets the same zones and gridpoints step after
// step (they stay in its core's cache); a thread done with its share takes chunks of the others'
// from their back ends. A loop ends when every chunk is done, not when every thread has arrived:
// a worker the system has not scheduled (another job on its core) is not waited for, the others
// take its share, and the loop costs at worst what one thread's would. Results do not depend on
// which thread ran a chunk (parallel.hpp keeps each chunk's sums apart and adds them in chunk
// order).
#include <atomic>
#include <cstdint>
#include <memory>
#include <thread>
#include <vector>

namespace vdec {

class ThreadTeam {
 public:
  // A chunk's work: body(context, chunk).
  using Body = void (*)(void* context, int chunk);

  // The process's team, one thread (no worker) until setThreadCount.
  static ThreadTeam& instance();

  // Starts or stops workers so that loops run on `count` threads (at least one).
  void setThreadCount(int count);
  int threadCount() const { return static_cast<int>(workers_.size()) + 1; }

  // Calls body(context, c) for every c in [0, chunks) on the team's threads and returns when all
  // are done. Not reentrant: a body may not run a loop of its own.
  void run(int chunks, Body body, void* context);

  ~ThreadTeam();

 private:
  ThreadTeam() = default;
  // A worker's loop: waits for a generation after `seen` and works on it as thread `self`.
  void work(int self, std::uint32_t seen);
  // Runs chunks of the loop of `generation`, this thread's share first, then the others'.
  void takeChunks(int self, std::uint32_t generation);

  // The generation of the loop being run; a new one wakes the workers.
  std::atomic<std::uint32_t> generation_{0};
  // Each thread's share of the loop's chunks: generation, front and back (the chunks
  // [front, back) not yet taken) packed in one word, so that a thread late for one loop cannot
  // take a chunk of the next.
  std::unique_ptr<std::atomic<std::uint64_t>[]> shares_;
  // The loop of each generation, by its parity: the loop of generation g + 2 is set up only after
  // every chunk of g was done, so a thread that took a chunk of g finds g's loop in its slot.
  struct Loop {
    std::atomic<Body> body{nullptr};
    std::atomic<void*> context{nullptr};
    std::atomic<int> done{0};
  };
  Loop loops_[2];
  std::atomic<bool> stopping_{false};
  std::vector<std::thread> workers_;
  // Whether a loop pays to share is measured, not assumed: another job on the machine can make
  // two threads slower than one (a polling worker takes a third of the cores from the calling
  // thread). Each loop body keeps the recent time per chunk run alone and run shared, and runs
  // the way that is faster; one loop in kProbeEvery runs the other way, to follow a change.
  struct Timing {
    Body body = nullptr;
    double alone = 0.0, shared = 0.0;  // s per chunk, running means; 0 until measured
    unsigned loops = 0;
  };
  std::vector<Timing> timings_;
  // Set while loops run alone by choice: an idle worker then sleeps at once instead of polling,
  // and leaves the core to the job that made sharing slow.
  std::atomic<bool> workersIdle_{false};
  static constexpr unsigned kProbeEvery = 64;
};

}  // namespace vdec
