// A phase definition resolved against the model: the materials, blocks and boundaries it names,
// its excavations tried on a copy of the model as the phase will find it.
#include <algorithm>
#include <cmath>

#include "scene/build_parts.hpp"

namespace vdec {

namespace {

JointStrengthChange jointStrength(const Model& m, const JointStrengthDefinition& d) {
  JointStrengthChange change;
  change.material = jointMaterialNamed(m, d.origin, "name", d.material);
  const JointMaterial& j = m.jointMaterials[change.material];
  if (j.law == JointLaw::ContinuouslyYielding)
    d.origin.fail("name", "joint material '" + d.material + "' is continuously yielding; a phase changes the friction, "
                          "cohesion and tension of the Coulomb and point-contact laws only");
  if (d.frictionDegrees) change.tanFriction = std::tan(radians(*d.frictionDegrees));
  change.cohesion = d.cohesion;
  change.tension = d.tension;
  if (j.law == JointLaw::PointContact && (d.cohesion.value_or(0.0) > 0 || d.tension.value_or(0.0) > 0))
    d.origin.fail(d.cohesion.value_or(0.0) > 0 ? "cohesion" : "tension",
                  "the point-contact law has no cohesion or tensile strength");
  return change;
}

std::pair<int, MohrCoulombProperties> blockStrength(const Model& m, const BlockStrengthDefinition& d) {
  const int material = blockMaterialNamed(m, d.origin, "name", d.material);
  if (!m.blockMaterials[material].elastic())
    d.origin.fail("friction", "Mohr-Coulomb plasticity needs the elastic constants too (young and poisson, or bulk and shear)");
  return {material, d.strength};
}

// `geometry`, when a phase before has excavated, is the model as it left it.
RigidBlockChange rigidBlock(const Model& m, const std::optional<Model>& geometry, const RigidBlockChangeDefinition& d) {
  RigidBlockChange change = d.change;
  change.block = blockNamed(m, d.origin, "name", d.block);
  if (m.blocks.deformable[change.block])
    d.origin.fail("name", "block '" + m.blocks.name[change.block] + "' is deformable: a phase holds, drives and loads "
                          "its gridpoints through [[phase.boundary]] tables");
  if (geometry && geometry->blocks.excavated(change.block))
    d.origin.fail("name", "block '" + m.blocks.name[change.block] + "' was excavated by an earlier phase: it takes "
                          "no fixity, drive or load");
  return change;
}

}  // namespace

Phase buildPhase(const PhaseDefinition& d, Model& m, std::optional<Model>& geometry, std::set<std::string>& active) {
  Phase phase;
  phase.name = d.name;
  phase.stop = d.stop;
  phase.requireEquilibrium = d.requireEquilibrium;
  PhaseChanges& c = phase.changes;
  c.gravity = d.gravity;
  c.massDamping = d.massDamping;
  c.adaptiveDamping = d.adaptiveDamping;
  c.resetDisplacements = d.resetDisplacements;
  c.resetVelocities = d.resetVelocities;
  c.localDamping = d.localDamping;
  c.staticSolve = d.staticSolve;
  for (const JointStrengthDefinition& j : d.jointStrengths) c.joints.push_back(jointStrength(m, j));
  const Structures& st = m.structures;
  for (const std::string& name : d.free) {
    if (!active.erase(name))
      d.origin.fail("free", "no boundary, beam, cable or bolt named '" + name + "' is active when the phase starts (give "
                            "[[boundary]], [[beam]], [[cable]], [[bolt]] or an earlier phase's table of that kind "
                            "with that name)");
    const auto beam = std::find_if(st.beams.begin(), st.beams.end(), [&](const Beam& b) { return b.name == name; });
    const auto cable = std::find_if(st.cables.begin(), st.cables.end(), [&](const Cable& b) { return b.name == name; });
    const auto bolt = std::find_if(st.bolts.begin(), st.bolts.end(), [&](const Bolt& b) { return b.name == name; });
    if (beam != st.beams.end()) c.freeBeams.push_back(static_cast<int>(beam - st.beams.begin()));
    else if (cable != st.cables.end()) c.freeCables.push_back(static_cast<int>(cable - st.cables.begin()));
    else if (bolt != st.bolts.end()) c.freeBolts.push_back(static_cast<int>(bolt - st.bolts.begin()));
    else c.freeBoundaries.push_back(name);
  }
  for (const BlockStrengthDefinition& b : d.blockStrengths) c.blockStrengths.push_back(blockStrength(m, b));
  for (const RigidBlockChangeDefinition& b : d.blocks) c.blocks.push_back(rigidBlock(m, geometry, b));
  for (const ExcavationDefinition& e : d.excavations) {
    const ExcavationRegion& region = e.region;
    if (!geometry) geometry = m;
    // Tried on the model as the scene places it: rigid blocks by their centroid, zones by theirs.
    Blocks& blocks = geometry->blocks;
    int removed = 0;
    for (int b = 0; b < blocks.size(); ++b)
      if (!blocks.deformable[b] && !blocks.excavated(b) && region.contains(blocks.centroid[b])) {
        blocks.driven[b] = DriveAll | Excavated;
        ++removed;
      }
    const bool zoned = geometry->zones.size() > 0;
    if (zoned) removed += excavateZones(*geometry, [&](Vec2 p) { return region.contains(p); }, region.where).removed;
    if (removed == 0)
      e.origin.failTable("removes nothing: no rigid block's centroid and no zone centroid lies in it when the phase "
                         "starts");
    if (zoned && geometry->zones.size() == 0) e.origin.failTable("removes every zone: the model would have none left");
    bool anyLeft = geometry->zones.size() > 0;
    for (int b = 0; b < blocks.size(); ++b) anyLeft = anyLeft || (!blocks.deformable[b] && !blocks.excavated(b));
    if (!anyLeft) e.origin.failTable("removes every block: the model would be empty");
    c.excavations.push_back(region);
  }
  for (const BoundaryDefinition& b : d.boundaries) {
    Model& selected = geometry ? *geometry : m;
    BoundaryCondition condition = resolveBoundary(b, selected);
    if (geometry) m.timeFunctions = geometry->timeFunctions;
    if (!condition.name.empty() && !active.insert(condition.name).second)
      b.origin.fail("name", "boundary '" + condition.name + "' is active when the phase starts; free it first with this "
                            "phase's free = [\"" + condition.name + "\"]");
    c.boundaries.push_back(std::move(condition));
  }
  if (d.flow && !m.flow.present) d.origin.fail("flow", "needs a [fluid] table: the scene has no fluid");
  c.flow = d.flow;
  for (const FlowBoundaryDefinition& b : d.flowBoundaries) {
    c.flowBoundaries.push_back(flowBoundary(m, b, d.gravity.value_or(m.gravity)));
    if (geometry) geometry->timeFunctions = m.timeFunctions;
    if (!c.flowBoundaries.back().name.empty() && !active.insert(c.flowBoundaries.back().name).second)
      b.origin.fail("name", "boundary '" + c.flowBoundaries.back().name + "' is active when the phase starts; free it first");
  }
  for (const BeamDefinition& b : d.beams) {
    if (active.count(b.name))
      b.origin.fail("name", "'" + b.name + "' names a support or boundary active when the phase starts: give the beam another");
    const int index = addBeam(m, b);
    active.insert(b.name);
    c.installBeams.push_back(index);
  }
  for (const BeamNodeDefinition& b : d.beamNodes) c.beamNodes.push_back(beamNodeChange(m, b));
  if (d.boundaryElements) {
    const Model& selected = geometry ? *geometry : m;
    c.boundaryElements = boundaryElementField(selected, *d.boundaryElements);
  }
  for (const CableDefinition& b : d.cables) {
    if (active.count(b.name))
      b.origin.fail("name", "'" + b.name + "' names a support or boundary active when the phase starts: give the cable another");
    c.installCables.push_back(addCable(m, b));
    active.insert(b.name);
  }
  for (const BoltDefinition& b : d.bolts) {
    if (active.count(b.name))
      b.origin.fail("name", "'" + b.name + "' names a support or boundary active when the phase starts: give the bolt another");
    c.installBolts.push_back(addBolt(m, b));
    active.insert(b.name);
  }
  return phase;
}

}  // namespace vdec
