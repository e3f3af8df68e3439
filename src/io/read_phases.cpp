// [[phase]] tables and the changes each makes at its start.
#include "io/scene_sections.hpp"

namespace vdec {

namespace {

JointStrengthDefinition readJointStrength(TableReader& r) {
  JointStrengthDefinition d;
  d.origin = r.origin();
  d.material = r.string("name");
  if (r.has("friction")) d.frictionDegrees = r.angleDegrees("friction", 0.0);
  if (r.has("cohesion")) d.cohesion = r.nonNegative("cohesion", 0.0);
  if (r.has("tension")) d.tension = r.nonNegative("tension", 0.0);
  r.finish();
  if (!d.frictionDegrees && !d.cohesion && !d.tension) r.failTable("changes nothing: give friction, cohesion and/or tension");
  return d;
}

BlockStrengthDefinition readBlockStrength(TableReader& r, std::vector<std::string>& warnings) {
  BlockStrengthDefinition d;
  d.origin = r.origin();
  d.material = r.string("name");
  const auto strength = readMohrCoulomb(r, warnings);
  r.finish();
  if (!strength)
    r.failTable("changes nothing: give the Mohr-Coulomb strength, friction and cohesion (and dilation, tension)");
  d.strength = *strength;
  return d;
}

RigidBlockChangeDefinition readRigidBlockChange(TableReader& r) {
  RigidBlockChangeDefinition d;
  d.origin = r.origin();
  d.block = r.string("name");
  RigidBlockChange& change = d.change;
  change.fix = r.has("fix") ? degreesOfFreedom(r, "fix") : 0;
  change.free = r.has("free") ? degreesOfFreedom(r, "free") : 0;
  if (change.fix & change.free) r.fail("free", "a degree of freedom is both fixed and freed");
  if (r.has("velocity") && !(change.fix & (DriveX | DriveY)))
    r.fail("velocity", "drives the components given in fix (\"x\", \"y\"); add them to fix");
  if (r.has("angular_velocity") && !(change.fix & DriveRotation))
    r.fail("angular_velocity", "drives the rotation: add \"rotation\" to fix");
  change.velocity = r.vec2("velocity", {0.0, 0.0});
  change.angularVelocity = r.number("angular_velocity", 0.0);
  if (r.has("force")) change.force = r.vec2("force");
  if (r.has("moment")) change.moment = r.number("moment");
  r.finish();
  if (!change.fix && !change.free && !change.force && !change.moment)
    r.failTable("changes nothing: give fix, free, force and/or moment");
  return d;
}

PhaseDefinition readPhase(TableReader& r, std::vector<std::string>& warnings) {
  PhaseDefinition d;
  d.origin = r.origin();
  d.name = r.string("name");
  auto stop = r.subtable("stop");
  if (!stop) r.fail("stop", "is required: each phase sets stop = { cycles, time or ratio }");
  d.stop = readStop(*stop);
  d.requireEquilibrium = r.boolean("require_equilibrium", false);
  if (d.requireEquilibrium && d.stop.ratio < 0)
    r.fail("require_equilibrium", "needs stop.ratio: equilibrium is the unbalanced-force ratio falling to it");
  if (r.has("gravity")) d.gravity = r.vec2("gravity");
  if (r.has("mass_damping") && r.has("adaptive_damping"))
    r.fail("mass_damping", "give mass_damping or adaptive_damping, not both");
  if (r.has("mass_damping")) d.massDamping = r.nonNegative("mass_damping", 0.0);
  if (r.has("adaptive_damping")) d.adaptiveDamping = r.boolean("adaptive_damping", false);
  if (r.has("local_damping")) {
    d.localDamping = r.number("local_damping");
    if (!(*d.localDamping >= 0.0 && *d.localDamping < 1.0))
      r.fail("local_damping", "must lie in [0, 1): the fraction of each out-of-balance force turned against the "
                              "motion (0.8 is the usual value; 0 switches local damping off)");
    if (*d.localDamping > 0.0 && (r.has("mass_damping") || d.adaptiveDamping.value_or(false)))
      r.fail("local_damping", "replaces mass damping; give local_damping or mass_damping / adaptive_damping, not both");
  }
  d.staticSolve = r.boolean("static_solve", false);
  for (const std::string& what : r.has("reset") ? r.strings("reset") : std::vector<std::string>{}) {
    if (what == "displacements") d.resetDisplacements = true;
    else if (what == "velocities") d.resetVelocities = true;
    else r.fail("reset", "unknown item '" + what + "'; use \"displacements\" and/or \"velocities\"");
  }
  for (auto [table, prefix] : r.tables("joint_material")) {
    TableReader t(*table, prefix, r.file());
    d.jointStrengths.push_back(readJointStrength(t));
  }
  if (r.has("free")) d.free = r.strings("free");
  for (auto [table, prefix] : r.tables("block_material")) {
    TableReader t(*table, prefix, r.file());
    d.blockStrengths.push_back(readBlockStrength(t, warnings));
  }
  for (auto [table, prefix] : r.tables("block")) {
    TableReader t(*table, prefix, r.file());
    d.blocks.push_back(readRigidBlockChange(t));
  }
  for (auto [table, prefix] : r.tables("excavation")) {
    TableReader t(*table, prefix, r.file());
    d.excavations.push_back(readExcavation(t));
    t.finish();
  }
  for (auto [table, prefix] : r.tables("boundary")) {
    TableReader t(*table, prefix, r.file());
    d.boundaries.push_back(readBoundary(t));
    t.finish();
  }
  for (auto [table, prefix] : r.tables("beam")) {
    TableReader t(*table, prefix, r.file());
    d.beams.push_back(readBeam(t));
  }
  for (auto [table, prefix] : r.tables("beam_node")) {
    TableReader t(*table, prefix, r.file());
    d.beamNodes.push_back(readBeamNode(t));
  }
  for (auto [table, prefix] : r.tables("cable")) {
    TableReader t(*table, prefix, r.file());
    d.cables.push_back(readCable(t));
  }
  if (auto t = r.subtable("boundary_elements")) d.boundaryElements = readBoundaryElements(*t);
  if (r.has("heat_time")) d.heatTime = r.nonNegative("heat_time", 0.0);
  for (auto [table, prefix] : r.tables("bolt")) {
    TableReader t(*table, prefix, r.file());
    d.bolts.push_back(readBolt(t));
  }
  if (r.has("flow")) d.flow = r.boolean("flow", true);
  for (auto [table, prefix] : r.tables("flow_boundary")) {
    TableReader t(*table, prefix, r.file());
    d.flowBoundaries.push_back(readFlowBoundary(t));
  }
  r.finish();
  return d;
}

}  // namespace

void readPhases(TableReader& top, SceneDefinition& scene) {
  for (auto [table, prefix] : top.tables("phase")) {
    TableReader r(*table, prefix, top.file());
    scene.phases.push_back(readPhase(r, scene.warnings));
  }
}

}  // namespace vdec
