#include "core/vector_unit.hpp"

#include <atomic>

namespace vdec {

bool vectorUnitSupported(VectorUnit unit) {
#if VDEC_VECTOR_UNITS
  switch (unit) {
    case VectorUnit::Avx512: return __builtin_cpu_supports("avx512f");
    case VectorUnit::Avx2: return __builtin_cpu_supports("avx2");
    case VectorUnit::Baseline: return true;
  }
  return false;
#else
  return unit == VectorUnit::Baseline;
#endif
}

VectorUnit widestVectorUnit() {
  for (const VectorUnit unit : {VectorUnit::Avx512, VectorUnit::Avx2})
    if (vectorUnitSupported(unit)) return unit;
  return VectorUnit::Baseline;
}

namespace {

std::atomic<VectorUnit>& chosen() {
  static std::atomic<VectorUnit> unit{widestVectorUnit()};
  return unit;
}

}  // namespace

VectorUnit vectorUnit() { return chosen().load(std::memory_order_relaxed); }

bool setVectorUnit(VectorUnit unit) {
  if (!vectorUnitSupported(unit)) return false;
  chosen().store(unit, std::memory_order_relaxed);
  return true;
}

const char* vectorUnitName(VectorUnit unit) {
  switch (unit) {
    case VectorUnit::Avx512: return "avx512";
    case VectorUnit::Avx2: return "avx2";
    case VectorUnit::Baseline: return "baseline";
  }
  return "baseline";
}

}  // namespace vdec
