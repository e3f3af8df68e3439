#pragma once
// Loops over zones and gridpoints on the run's threads with results that do not depend on the
// number of threads: every element writes only its own slots, and reductions are formed per
// fixed-size chunk and then combined in chunk order, so the additions happen in the same order at
// 1 or N threads.
#include <cstddef>
#include <vector>

namespace vdec {

inline constexpr int kReduceChunk = 1024;

// The work of a step that the threads share: the zone-forces and gridpoint-motion loops, over
// zones and gridpoints. Contacts are computed on one thread and do not count.
// Below kWorkForThreads elements per step a second thread does not pay: with idle threads
// sleeping (OMP_WAIT_POLICY=passive, as vdec sets it) every loop wakes the other thread, which
// takes tens of microseconds, and waits for it at the loop's end. Measured on an idle 2-core
// machine: two threads 1.00 times as fast as one at 21 721 elements, 1.21 times at 30 389
// (docs/performance.md#threads).
inline constexpr long long kWorkForThreads = 30000;

// The thread count for a run that does not set one: one below kWorkForThreads, else all
// `available` (the OpenMP maximum: OMP_NUM_THREADS, or the number of processors).
inline int automaticThreadCount(long long workPerStep, int available) {
  return workPerStep < kWorkForThreads || available < 1 ? 1 : available;
}

// Calls f(i, acc) for i in [0, n), each chunk with its own accumulator starting from T{}, and
// combines the chunk accumulators in order with combine(total, chunk). f must write only to
// data owned by element i (and to acc).
// The same, with f called once per chunk as f(begin, end, acc), for loops that work on several
// elements at a time.
template <class T, class F, class Combine>
T deterministicReduceChunks(int n, F&& f, Combine&& combine) {
  const int chunks = (n + kReduceChunk - 1) / kReduceChunk;
  // Kept from call to call (per calling thread and type): no allocation once the model is running.
  // The worker threads reach it through this reference: their own thread_local copies are empty.
  static thread_local std::vector<T> buffer;
  std::vector<T>& partial = buffer;
  partial.assign(static_cast<std::size_t>(chunks), T{});
  // One chunk is not worth waking the other threads for.
#pragma omp parallel for schedule(static) if (chunks > 1)
  for (int c = 0; c < chunks; ++c) {
    const int end = (c + 1) * kReduceChunk < n ? (c + 1) * kReduceChunk : n;
    T acc{};
    f(c * kReduceChunk, end, acc);
    partial[static_cast<std::size_t>(c)] = acc;
  }
  T total{};
  for (const T& p : partial) combine(total, p);
  return total;
}

template <class T, class F, class Combine>
T deterministicReduce(int n, F&& f, Combine&& combine) {
  return deterministicReduceChunks<T>(
      n, [&](int begin, int end, T& acc) {
        for (int i = begin; i < end; ++i) f(i, acc);
      },
      combine);
}

// The sum of f(i) over [0, n), bitwise the same at any thread count.
template <class F>
double deterministicSum(int n, F&& f) {
  return deterministicReduce<double>(
      n, [&](int i, double& acc) { acc += f(i); }, [](double& total, double part) { total += part; });
}

}  // namespace vdec
