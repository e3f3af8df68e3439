#pragma once
// results.json (schema vdec.results/1): provenance, run summary, histories, final state.
#include <string>

#include "core/cycle.hpp"
#include "io/scene_reader.hpp"

namespace vdec {

// Writes dir/results.json, creating dir. Throws OutputError naming the path on failure.
void writeResults(const std::string& dir, const Scene& scene, const RunReport& report, double setupSeconds);

}  // namespace vdec
