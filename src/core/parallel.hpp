#pragma once
// Loops over zones and gridpoints on the run's threads with results that do not depend on the
// number of threads: every element writes only its own slots, and reductions are formed per
// fixed-size chunk and then combined in chunk order, so the additions happen in the same order at
// 1 or N threads.
#include <cstddef>
#include <cstdlib>
#include <thread>
#include <type_traits>
#include <vector>

#include "core/model.hpp"
#include "core/thread_team.hpp"

namespace vdec {

inline constexpr int kReduceChunk = 256;

// The work of a step that the threads share: the zone-forces and gridpoint-motion loops, over
// zones and gridpoints, and the contact updates, counted as three elements per block corner
// (a contact costs about three zones, and a lattice has about one and a half contacts per
// corner) when there is more than one block to touch.
// Below kWorkForThreads elements per step a second thread does not pay: a loop's chunks are then
// few, and with another job on the machine two threads lost 5 % there. Measured on a 2-core
// machine: two threads 1.6 times as fast as one at 3 800 elements (2 500 zones) when idle, 0.95
// with one core busy; 1.7 and 0.99 at 15 000; a 1 000-block lattice (12 000) 1.4 times as fast
// (docs/performance.md#threads).
inline constexpr long long kWorkForThreads = 8000;

inline long long workPerStep(const Model& m) {
  const long long corners = m.blocks.size() > 1 ? m.vertices.size() : 0;
  return static_cast<long long>(m.zones.size()) + m.gridpoints.size() + 3 * corners;
}

// The thread count for a run that does not set one: one below kWorkForThreads, else all
// `available` (availableThreads()).
inline int automaticThreadCount(long long workPerStep, int available) {
  return workPerStep < kWorkForThreads || available < 1 ? 1 : available;
}

// OMP_NUM_THREADS when it is a positive count (the variable users of threaded codes set), else
// the number of processors.
inline int availableThreads() {
  if (const char* value = std::getenv("OMP_NUM_THREADS")) {
    char* end = nullptr;
    const long count = std::strtol(value, &end, 10);
    if (end != value && *end == '\0' && count > 0 && count <= 1024) return static_cast<int>(count);
  }
  const unsigned processors = std::thread::hardware_concurrency();
  return processors > 0 ? static_cast<int>(processors) : 1;
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
  struct Loop {
    std::remove_reference_t<F>* f;
    std::vector<T>* partial;
    int n;
  } loop{&f, &partial, n};
  ThreadTeam::instance().run(chunks, [](void* context, int c) {
    const Loop& l = *static_cast<const Loop*>(context);
    const int end = (c + 1) * kReduceChunk < l.n ? (c + 1) * kReduceChunk : l.n;
    T acc{};
    (*l.f)(c * kReduceChunk, end, acc);
    (*l.partial)[static_cast<std::size_t>(c)] = acc;
  }, &loop);
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
