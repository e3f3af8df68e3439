// [solver], [stop] and [output].
#include <numbers>

#include "io/scene_sections.hpp"

namespace vdec {

StopCriteria readStop(TableReader& t) {
  StopCriteria s;
  if (t.has("cycles")) {
    s.cycles = t.integer("cycles");
    if (s.cycles <= 0) t.fail("cycles", "must be > 0");
  }
  if (t.has("time")) s.time = t.positive("time");
  if (t.has("ratio")) s.ratio = t.positive("ratio");
  if (s.cycles < 0 && s.time < 0 && s.ratio < 0) t.failTable("set at least one of cycles, time or ratio");
  if (s.ratio > 0 && s.cycles < 0 && s.time < 0)
    t.fail("ratio", "needs a limit as well: set cycles or time, so that a run that never reaches the ratio ends");
  t.finish();
  return s;
}

namespace {

void readSolver(TableReader& t, RunSettings& settings) {
  settings.frac = t.number("frac", 0.1);
  if (!(settings.frac > 0 && settings.frac <= 10)) t.fail("frac", "must be in (0, 10], got " + shown(settings.frac));
  settings.zoneFraction = t.number("zone_fraction", 1.0);
  if (!(settings.zoneFraction > 0 && settings.zoneFraction <= 10))
    t.fail("zone_fraction", "must be in (0, 10], got " + shown(settings.zoneFraction));
  settings.massDamping = t.nonNegative("mass_damping", 0.0);
  settings.adaptiveDamping = t.boolean("adaptive_damping", false);
  if (t.has("local_damping")) {
    settings.localDamping = t.number("local_damping");
    if (!(settings.localDamping > 0.0 && settings.localDamping < 1.0))
      t.fail("local_damping", "must lie in (0, 1): the fraction of each out-of-balance force turned against the motion "
                              "(0.8 is the usual value)");
    if (t.has("mass_damping") || settings.adaptiveDamping)
      t.fail("local_damping", "replaces mass damping; give local_damping or mass_damping / adaptive_damping, not both");
  }
  if (settings.adaptiveDamping && t.has("mass_damping"))
    t.fail("mass_damping", "adaptive_damping sets the mass damping itself; give one or the other");
  if (t.has("stiffness_damping") && t.has("rayleigh"))
    t.fail("rayleigh", "sets the stiffness damping itself; give rayleigh or stiffness_damping, not both");
  if (t.has("stiffness_damping")) settings.stiffnessDamping = t.nonNegative("stiffness_damping", 0.0);
  if (t.has("rayleigh")) {
    if (t.has("mass_damping"))
      t.fail("rayleigh", "sets the mass damping itself; give rayleigh, or mass_damping with stiffness_damping");
    auto ray = t.subtable("rayleigh");
    if (!ray) t.fail("rayleigh", "must be a table { ratio = XI, frequency = F }");
    const double ratio = ray->number("ratio"), frequency = ray->positive("frequency");
    if (!(ratio > 0.0 && ratio < 1.0)) ray->fail("ratio", "must be in (0, 1): the critical-damping ratio at the frequency");
    ray->finish();
    // xi(w) = (alpha / w + beta w) / 2 is smallest, xi, at w_min = 2 pi f (1.3-18, 1.3-19).
    const double w = 2.0 * std::numbers::pi * frequency;
    settings.massDamping = ratio * w;
    settings.stiffnessDamping = ratio / w;
  }
  if (settings.stiffnessDamping > 0.0 && (settings.adaptiveDamping || t.has("local_damping")))
    t.fail(t.has("rayleigh") ? "rayleigh" : "stiffness_damping",
           "goes with mass damping (Rayleigh damping), not with adaptive or local damping");
  settings.densityScaling = t.boolean("density_scaling", false);
  settings.staticSolve = t.boolean("static_solve", false);
  t.finish();
}

}  // namespace

void readRunSettings(TableReader& top, SceneDefinition& scene) {
  RunSettings& settings = scene.settings;
  if (auto t = top.subtable("solver")) {
    scene.solver = t->origin();
    readSolver(*t, settings);
  }
  if (top.has("phase")) {
    if (top.has("stop"))
      top.fail("stop", "with [[phase]] tables each phase has its own stop; move [stop] into the phases and remove it");
  } else {
    auto t = top.subtable("stop");
    if (!t) top.fail("stop", "is required: set [stop] cycles, time or ratio (or give [[phase]] tables, each with its stop)");
    settings.stop = readStop(*t);
  }
  if (auto t = top.subtable("output")) {
    if (t->has("vtk_every")) {
      const long long every = t->integer("vtk_every");
      if (every < 1) t->fail("vtk_every", "must be >= 1 (cycles between VTK snapshots)");
      settings.snapshotEvery = every;
    }
    t->finish();
  }
}

}  // namespace vdec
