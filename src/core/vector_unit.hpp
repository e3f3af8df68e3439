#pragma once
// The element loops that take nearly all of a deformable block's cycle (zone forces, gridpoint
// motion) are compiled once per x86-64 vector unit: AVX-512, AVX2 and the baseline (SSE2). At
// start-up the widest the processor has is chosen. Only the width of the vector registers
// differs: every version performs the same IEEE-754 operations in the same order (no
// reassociation, and no fused multiply-add: -ffp-contract=off in CMakeLists.txt), so a scene's
// results are bitwise the same whichever runs; tests/unit/test_vector_unit.cpp checks it.
// Measured in docs/performance.md#cycle-cost.
namespace vdec {

enum class VectorUnit { Baseline, Avx2, Avx512 };

// The unit the loops use now: the widest the processor supports unless set otherwise.
VectorUnit vectorUnit();
// For tests and benchmarks; a unit the processor lacks is refused (returns false).
bool setVectorUnit(VectorUnit unit);
bool vectorUnitSupported(VectorUnit unit);
VectorUnit widestVectorUnit();
const char* vectorUnitName(VectorUnit unit);

}  // namespace vdec

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define VDEC_VECTOR_UNITS 1
// A kernel's versions are wrappers, each with one of these, around one always-inlined body.
#define VDEC_TARGET_AVX512 __attribute__((target("avx512f")))
#define VDEC_TARGET_AVX2 __attribute__((target("avx2")))
#else
#define VDEC_VECTOR_UNITS 0
#endif
