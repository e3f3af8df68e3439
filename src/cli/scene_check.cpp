#include "cli/scene_check.hpp"

#include <cstdio>
#include <filesystem>
#include <string>

#include "core/errors.hpp"
#include "io/results_writer.hpp"
#include "io/scene_reader.hpp"
#include "io/vtk_writer.hpp"
#include "run/cycle.hpp"

namespace vdec {

namespace {

std::string stopText(const StopCriteria& s) {
  std::string text;
  auto add = [&text](const std::string& part) { text += (text.empty() ? "" : ", ") + part; };
  char buffer[64];
  if (s.cycles >= 0) add(std::to_string(s.cycles) + " cycles");
  if (s.time >= 0) std::snprintf(buffer, sizeof buffer, "time %g s", s.time), add(buffer);
  if (s.ratio >= 0) std::snprintf(buffer, sizeof buffer, "ratio %g", s.ratio), add(buffer);
  return text.empty() ? "none" : text;
}

std::string phaseChanges(const PhaseChanges& c) {
  std::string text;
  auto add = [&text](const std::string& part) { text += (text.empty() ? "" : "; ") + part; };
  if (c.gravity) add("gravity");
  if (!c.excavations.empty()) add(std::to_string(c.excavations.size()) + " excavation(s)");
  if (!c.boundaries.empty()) add(std::to_string(c.boundaries.size()) + " boundary condition(s)");
  if (!c.freeBoundaries.empty()) add(std::to_string(c.freeBoundaries.size()) + " freed");
  if (c.staticSolve) add("direct solve");
  if (c.boundaryElements) add("far field");
  if (c.heatTime > 0.0) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "heat time %g s", c.heatTime);
    add(buffer);
  }
  return text.empty() ? "" : " (" + text + ")";
}

}  // namespace

int checkScene(const std::string& path, const std::vector<std::string>& overrides, const std::string& vtkDirectory) {
  Scene scene = readScene(path, overrides);
  for (const std::string& w : scene.warnings) std::fprintf(stderr, "vdec: warning: %s\n", w.c_str());
  RunSettings settings = scene.settings;
  // The direct solve is what a run does first; check reports it without making it.
  const bool directSolve = settings.staticSolve;
  settings.staticSolve = false;
  settings.progress = false;
  const Model& m = scene.model;
  Cycle cycle(scene.model, settings, scene.histories);

  std::printf("scene %s\n  sha256 %s\n", scene.path.c_str(), scene.sha256.c_str());
  if (!scene.title.empty()) std::printf("  title %s\n", scene.title.c_str());
  int rigid = 0, free = 0, strained = 0, zoned = 0;
  for (int b = 0; b < m.blocks.size(); ++b) {
    if (m.blocks.deformable[b]) ++zoned;
    else if (m.strainModes.holds(b)) ++strained;
    else ++rigid;
    if (m.blocks.movesFreely(b)) ++free;
  }
  std::printf("blocks %d: %d rigid, %d simply-deformable, %d zoned; %d free to move\n", m.blocks.size(), rigid,
              strained, zoned, free);
  std::printf("zones %d, gridpoints %d\n", m.zones.size(), m.gridpoints.size());
  for (const BlockMaterial& mat : m.blockMaterials) {
    std::printf("block material '%s': density %g kg/m^3", mat.name.c_str(), mat.density);
    if (mat.elastic()) std::printf(", K %g Pa, G %g Pa", mat.bulk, mat.shear);
    std::printf("%s\n", mat.plastic ? ", Mohr-Coulomb" : "");
  }
  for (const JointMaterial& j : m.jointMaterials)
    std::printf("joint material '%s': %s, kn %g, ks %g\n", j.name.c_str(), jointLawName(j.law), j.kn, j.ks);
  int closed = 0;
  for (const Contact& c : m.contacts) closed += c.open ? 0 : 1;
  std::printf("contacts at the start %zu, %d closed\n", m.contacts.size(), closed);
  std::printf("time step %g s\n", cycle.timeStep());
  for (const auto& [component, limit] : cycle.stepLimits())
    std::printf("  limit of %s %g s\n", component.c_str(), limit);
  std::string stages;
  for (const std::string& s : cycle.stageNames()) stages += (stages.empty() ? "" : ", ") + s;
  std::printf("stages %s\n", stages.c_str());
  if (directSolve) std::printf("direct solve before the first cycle (solver.static_solve)\n");
  if (m.heat.on)
    std::printf("heat: %d thermal nodes, theta %g, step %g s (explicit limit %g s)\n", m.heat.size(), m.heat.theta,
                m.heat.step, m.heat.stableStep);
  if (scene.settings.phases.empty()) {
    std::printf("run: stop at %s\n", stopText(scene.settings.stop).c_str());
  } else {
    for (std::size_t k = 0; k < scene.settings.phases.size(); ++k) {
      const Phase& p = scene.settings.phases[k];
      std::printf("phase %zu '%s': stop at %s%s\n", k + 1, p.name.c_str(), stopText(p.stop).c_str(),
                  phaseChanges(p.changes).c_str());
    }
  }
  std::printf("histories %zu\n", scene.histories.size());
  if (!vtkDirectory.empty()) {
    // Made here so that a bad directory is named as the --vtk option's, not a run's --out.
    std::error_code error;
    std::filesystem::create_directories(vtkDirectory, error);
    if (error || !std::filesystem::is_directory(vtkDirectory))
      throw OutputError(vtkDirectory + ": cannot create this --vtk directory (" +
                        (error ? error.message() : std::string("a file of that name is in the way")) +
                        "); choose another");
    VtkSeries::removeStale(vtkDirectory);
    VtkSeries series(vtkDirectory);
    series.prepare();
    series.write(scene.model);
    std::printf("model at cycle 0 written to %s/snapshot_000000000.vtu\n", vtkDirectory.c_str());
  }
  return 0;
}

}  // namespace vdec
