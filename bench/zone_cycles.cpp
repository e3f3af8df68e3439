// Runs the benchmark's elastic block (bench/elastic_zone_bench.cpp: 10 m square, E = 10 GPa,
// nu = 0.25, fixed base, 1 MPa on top, mass damping 400 1/s) for a given number of cycles on a
// given vector unit, for instruction counts under valgrind, which times nothing:
//
//   valgrind --tool=callgrind vdec_zone_cycles UNIT CYCLES [N]
//
// UNIT 0 is the SSE2 baseline, 1 AVX2, 2 AVX-512 (valgrind has no AVX-512); N x N crossed cells,
// 50 unless given. The difference of two runs' counts (say 300 and 100 cycles) over the zones
// and the cycles between is the count per zone-cycle (docs/performance.md#cycle-cost).
#include <cstdlib>
#include <iostream>

#include "core/vector_unit.hpp"
#include "run/cycle.hpp"
#include "elastic_block.hpp"

int main(int argc, char** argv) {
  if (argc < 3) {
    std::cerr << "usage: vdec_zone_cycles UNIT CYCLES [N]\n";
    return 2;
  }
  const int unit = std::atoi(argv[1]);
  const long long cycles = std::atoll(argv[2]);
  const int n = argc > 3 ? std::atoi(argv[3]) : 50;
  if (unit < 0 || unit > 2 || cycles < 1 || n < 1) {
    std::cerr << "vdec_zone_cycles: UNIT must be 0, 1 or 2, CYCLES and N positive\n";
    return 2;
  }
  if (!vdec::setVectorUnit(static_cast<vdec::VectorUnit>(unit))) {
    std::cerr << "vdec_zone_cycles: this processor has no "
              << vdec::vectorUnitName(static_cast<vdec::VectorUnit>(unit)) << "\n";
    return 3;
  }
  vdec::Scene scene = vdec::bench::elasticBlock(n);
  scene.settings.stop = {};
  scene.settings.stop.cycles = cycles;
  vdec::Cycle cycle(scene.model, scene.settings, {});
  const vdec::RunReport report = cycle.run();
  std::cout << vdec::vectorUnitName(vdec::vectorUnit()) << ": " << scene.model.zones.size() << " zones, "
            << scene.model.gridpoints.size() << " gridpoints, " << scene.model.cycle << " cycles\n";
  if (!report.error.empty()) {
    std::cerr << report.error << "\n";
    return 1;
  }
  return 0;
}
