// vdec: the command-line front end. `vdec run SCENE --out DIR` reads a scene, runs it and
// writes DIR/results.json; the exit code says what went wrong (core/errors.hpp).
#include <CLI/CLI.hpp>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "cli/python_tools.hpp"
#include "cli/scene_check.hpp"
#include "run/cycle.hpp"
#include "core/errors.hpp"
#include "core/interrupt.hpp"
#include "core/parallel.hpp"
#include "core/thread_team.hpp"
#include "io/build_info.hpp"
#include "io/results_writer.hpp"
#include "io/scene_reader.hpp"
#include "io/state_file.hpp"
#include "io/vtk_writer.hpp"

namespace {

struct RunOptions {
  std::string scenePath, outDir;
  std::vector<std::string> overrides;
  bool profile = false;
  int threads = 0;  // 0: chosen from the work
  std::vector<std::string> save;  // phases after which the state is written
  std::string restart;            // a state file to continue from
};

// The phase index (1-based) of each name given to --save; the names must be the scene's phases.
std::vector<int> phasesToSave(const RunOptions& options, const vdec::Scene& scene) {
  std::vector<int> indices;
  for (const std::string& name : options.save) {
    int found = 0;
    for (std::size_t k = 0; k < scene.settings.phases.size(); ++k)
      if (scene.settings.phases[k].name == name) found = static_cast<int>(k) + 1;
    if (found == 0) {
      std::string names;
      for (const auto& p : scene.settings.phases) names += (names.empty() ? "'" : ", '") + p.name + "'";
      throw vdec::Error(vdec::ExitCode::Usage,
                        "--save " + name + ": " + scene.path +
                            (names.empty() ? " has no [[phase]] tables; a state is saved after a phase"
                                           : " has no phase of that name (its phases: " + names + ")"));
    }
    indices.push_back(found);
  }
  return indices;
}

int runScene(const RunOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const std::string& outDir = options.outDir;
  // Before the scene is read: a bad directory fails at once, and the results of an earlier run
  // are gone before this one can fail.
  vdec::prepareOutputDirectory(outDir);
  vdec::VtkSeries vtk((std::filesystem::path(outDir) / "vtk").string());
  vdec::VtkSeries::removeStale((std::filesystem::path(outDir) / "vtk").string());
  vdec::Scene scene = vdec::readScene(options.scenePath, options.overrides);
  for (const std::string& w : scene.warnings) std::fprintf(stderr, "vdec: warning: %s\n", w.c_str());
  scene.settings.profile = options.profile;
  scene.settings.progress = true;
  if (scene.settings.snapshotEvery > 0) vtk.prepare();
  scene.settings.snapshot = [&vtk](const vdec::Model& model) { vtk.write(model); };
  vdec::RunEnvironment environment;
  environment.threadsOption = options.threads;
  environment.threads = options.threads > 0 ? options.threads
                        : vdec::automaticThreadCount(vdec::workPerStep(scene.model), vdec::availableThreads());
  vdec::ThreadTeam::instance().setThreadCount(environment.threads);
  const std::vector<int> saveAfter = phasesToSave(options, scene);
  vdec::Cycle cycle(scene.model, scene.settings, scene.histories);
  if (!options.restart.empty()) {
    if (scene.settings.phases.empty())
      throw vdec::RestartError(options.restart + ": " + scene.path +
                               " has no [[phase]] tables; a restart continues a scene's phases");
    const auto loadStart = std::chrono::steady_clock::now();
    const int done = vdec::readState(options.restart, scene, scene.model, cycle);
    std::fprintf(stderr, "vdec: continuing after phase '%s' from %s (%.1f MB read in %.3f s)\n",
                 scene.settings.phases[done - 1].name.c_str(), options.restart.c_str(),
                 static_cast<double>(std::filesystem::file_size(options.restart)) / 1e6,
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - loadStart).count());
    cycle.resumeAt(done);
    environment.restartFile = options.restart;
    environment.restartPhases = done;
    for (const int k : saveAfter)
      if (k <= done)
        throw vdec::Error(vdec::ExitCode::Usage, "--save " + scene.settings.phases[k - 1].name + ": that phase ran before "
                                                 "the state in " + options.restart + " was saved");
  }
  cycle.afterPhase = [&](const std::string& name, const vdec::RunReport&) {
    for (const int k : saveAfter)
      if (scene.settings.phases[k - 1].name == name) {
        const std::string file = (std::filesystem::path(outDir) / ("after-phase-" + std::to_string(k) + ".vdecstate")).string();
        const auto saveStart = std::chrono::steady_clock::now();
        vdec::writeState(file, scene, scene.model, cycle, k);
        std::fprintf(stderr, "vdec: state after phase '%s' written to %s (%.1f MB in %.3f s)\n", name.c_str(),
                     file.c_str(), static_cast<double>(std::filesystem::file_size(file)) / 1e6,
                     std::chrono::duration<double>(std::chrono::steady_clock::now() - saveStart).count());
      }
  };
  const double setup = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const vdec::RunReport report = cycle.run();
  vdec::writeResults(outDir, scene, report, setup, environment);
  if (options.profile) {
    std::fprintf(stderr, "stage               seconds    share   ns/cycle\n");
    double total = 0.0;
    for (const auto& s : report.profile) total += s.seconds;
    for (const auto& s : report.profile)
      std::fprintf(stderr, "%-18s %9.4f %7.1f%% %10.1f\n", s.name.c_str(), s.seconds,
                   total > 0 ? 100.0 * s.seconds / total : 0.0,
                   report.cycles ? 1e9 * s.seconds / static_cast<double>(report.cycles) : 0.0);
    std::fprintf(stderr, "cycles %lld, contacts %zu, blocks %d, detection scans %d, threads %d\n", report.cycles,
                 scene.model.contacts.size(), scene.model.blocks.size(), report.detectionScans, environment.threads);
  }
  if (report.interruptSignal != 0) {
    std::fprintf(stderr, "vdec: interrupted by %s at cycle %lld, time %g s\n(results up to it written to %s/results.json)\n",
                 vdec::signalName(report.interruptSignal), report.cycles, report.time, outDir.c_str());
    return report.errorCode;
  }
  const double ratio = scene.settings.stop.ratio;
  if (report.errorCode == 0 && ratio > 0 && report.stopReason != "ratio")
    std::fprintf(stderr, "vdec: warning: stopped on %s before the unbalanced-force ratio fell to %g (last %.3e): "
                 "the model may not be in equilibrium\n", report.stopReason.c_str(), ratio,
                 report.lastMonitors.unbalancedRatio);
  for (std::size_t i = 0; i < report.phases.size(); ++i) {
    const vdec::PhaseReport& p = report.phases[i];
    const double phaseRatio = scene.settings.phases[i].stop.ratio;
    if (phaseRatio > 0 && (p.stopReason == "cycles" || p.stopReason == "time"))
      std::fprintf(stderr, "vdec: warning: phase '%s' stopped on %s before the unbalanced-force ratio fell to %g "
                   "(last %.3e): the model may not be in equilibrium\n", p.name.c_str(), p.stopReason.c_str(),
                   phaseRatio, p.unbalancedRatio);
  }
  if (report.staticSolvePlasticFailed)
    std::fprintf(stderr, "vdec: warning: the direct solve found no equilibrium of the plastic zones (residual %.3e of "
                 "the forces when it gave up): the load may be at or beyond collapse; that solve left the model as it "
                 "was and the explicit cycles went on from there\n", report.staticSolveResidual);
  else if (report.staticSolveResidual > 1e-6)
    std::fprintf(stderr, "vdec: warning: the direct solve did not converge (last residual %.3e of the forces): joints "
                 "slipped or opened under its load, which its linear springs do not follow; the explicit cycles went "
                 "on from its last state\n", report.staticSolveResidual);
  if (report.errorCode != 0) {
    std::fprintf(stderr, "vdec: error: %s\n(results up to the failure written to %s/results.json)\n",
                 report.error.c_str(), outDir.c_str());
    return report.errorCode;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"vdec: Verified Distinct Element Code, a 2D distinct element code for jointed rock"};
  app.set_version_flag("--version", std::string("vdec ") + vdec::build::version + " (" + vdec::build::gitCommit +
                                        ", " + vdec::build::buildType + ", " + vdec::build::compiler + ")");
  app.require_subcommand(1);
  RunOptions options;
  CLI::App* run = app.add_subcommand("run", "run a scene and write DIR/results.json");
  run->add_option("scene", options.scenePath, "scene file (TOML)")->required();
  run->add_option("--out", options.outDir, "output directory")
      ->required()
      ->check([](const std::string& dir) {
        return dir.empty() ? std::string("the output directory is empty; give one, e.g. --out out") : std::string();
      });
  run->add_option("--set", options.overrides, "override a scene key, e.g. --set solver.frac=0.2 (repeatable)");
  run->add_flag("--profile", options.profile, "print the time spent in each stage of the cycle");
  run->add_option("--threads", options.threads,
                  "threads for the zone and gridpoint loops; 0 (the default): one for a small model, "
                  "else OMP_NUM_THREADS or every processor")
      ->check(CLI::Range(0, 1024));
  run->add_option("--save", options.save,
                  "write the state after these phases (comma-separated names) to DIR/after-phase-K.vdecstate")
      ->delimiter(',');
  run->add_option("--restart", options.restart, "continue the scene's phases from a state file written by --save");
  std::string checkPath;
  std::vector<std::string> checkOverrides;
  CLI::App* check = app.add_subcommand("check", "read and build a scene and print what a run would do, without running it");
  check->add_option("scene", checkPath, "scene file (TOML)")->required();
  check->add_option("--set", checkOverrides, "override a scene key, as for run (repeatable)");
  std::string checkVtk;
  check->add_option("--vtk", checkVtk,
                    "also write the built model as a cycle-0 VTK snapshot into this directory (for `vdec plot`)");
  // Their own options are parsed by the Python programs (`vdec plot --help`).
  CLI::App* plot = app.add_subcommand("plot", "draw a run's results (geometry, joints, forces, stresses, histories)");
  CLI::App* sweep = app.add_subcommand("sweep", "run a scene over a product of --set values or seeds, locally or on Slurm");
  for (CLI::App* tool : {plot, sweep}) {
    tool->prefix_command();
    tool->allow_extras();
    tool->set_help_flag();
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : static_cast<int>(vdec::ExitCode::Usage);
  }
  if (plot->parsed() || sweep->parsed()) {
    CLI::App* tool = plot->parsed() ? plot : sweep;
    return vdec::runPythonTool(tool->get_name(), tool->remaining());
  }
  // From here a signal stops the run between two steps, with the results so far written.
  vdec::installInterruptHandlers();
  try {
    if (check->parsed()) return vdec::checkScene(checkPath, checkOverrides, checkVtk);
    return runScene(options);
  } catch (const vdec::Error& e) {
    std::fprintf(stderr, "vdec: error: %s\n", e.what());
    return static_cast<int>(e.code());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vdec: internal error: %s\n", e.what());
    return static_cast<int>(vdec::ExitCode::Internal);
  }
}
