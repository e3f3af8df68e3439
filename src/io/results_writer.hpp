#pragma once
// results.json (schema vdec.results/1): provenance, run summary, histories, final state.
#include <string>

#include "run/cycle.hpp"
#include "io/scene_reader.hpp"

namespace vdec {

// Makes DIR ready before the scene is read, so that a bad directory fails at once: created if
// missing, a directory (a symlink to one is followed), a file can be created in it. Removes
// DIR/results.json of an earlier run (a symlink there is removed, not its target), so that a run
// that fails before it has results leaves none. Throws OutputError naming the path.
void prepareOutputDirectory(const std::string& dir);

// How the run was carried out: provenance for the environment object (it differs between runs
// of one scene; the results do not).
struct RunEnvironment {
  int threads = 1;        // threads the run's loops used (core/thread_team.hpp)
  int threadsOption = 0;  // --threads as given; 0: chosen from the work
  std::string restartFile;  // the state file the run continued from (--restart), else empty
  int restartPhases = 0;    // the phases done in it
};

// Writes dir/results.json under a temporary name renamed over it (io/atomic_file.hpp), creating
// dir. Throws OutputError naming the path on failure.
// A joint law as the scene names it (`law` of [[joint_material]]).
const char* jointLawName(JointLaw law);

void writeResults(const std::string& dir, const Scene& scene, const RunReport& report, double setupSeconds,
                  const RunEnvironment& environment);

}  // namespace vdec
