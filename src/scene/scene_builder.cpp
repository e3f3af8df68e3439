#include "scene/scene_builder.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>

#include "bem/far_field.hpp"
#include "boundary/boundary_conditions.hpp"
#include "contact/contact_geometry.hpp"
#include "contact/deformable_outline.hpp"
#include "core/errors.hpp"
#include "core/setup_progress.hpp"
#include "geometry/block_cutting.hpp"
#include "geometry/polygon.hpp"
#include "motion/strain_modes.hpp"
#include "scene/build_parts.hpp"
#include "core/shown.hpp"

namespace vdec {

namespace {

// A block on its way into the model: explicit, or cut from a region; excavation may still
// remove it or some of its zones.
struct BlockInput {
  const BlockDefinition* definition = nullptr;  // null for a block cut from a region
  std::string name;
  int material = -1;
  Polygon polygon;
  std::optional<Mesh> mesh;  // a deformable block's zoning
  std::string where;         // for geometry errors
  const Origin* simplyDeformable = nullptr;  // the table that made it simply deformable
};

// A block's area, mass and moment of inertia as formed from its shape and its material's
// density: an error naming the block (`where`) and the density's key unless they are finite
// and positive (a density of 1e308 times an area overflows).
void checkMassProperties(const Model& m, const std::string& where, int material, double area, double mass,
                         double inertia) {
  const BlockMaterial& mat = m.blockMaterials[material];
  const std::string density = "block_material[" + std::to_string(material) + "].density";
  if (!(std::isfinite(area) && area > 0.0))
    throw SceneError(where + ": its area, " + shown(area) + " m^2, is not a finite positive number: the coordinates "
                     "of its vertices are too large; give them in m, below about 1e150");
  if (!(std::isfinite(mass) && mass > 0.0))
    throw SceneError(where + ": its mass, " + density + " (" + shown(mat.density) + " kg/m^3) times its area (" +
                     shown(area) + " m^2), is " + shown(mass) + " kg/m, not a finite positive number: lower " + density);
  if (!(std::isfinite(inertia) && inertia >= 0.0))
    throw SceneError(where + ": its moment of inertia, " + density + " (" + shown(mat.density) +
                     " kg/m^3) times the polar second moment of its area, is " + shown(inertia) +
                     " kg m, not a finite number: lower " + density + " or the size of the block");
}

// What a new entry of Blocks is made from; the rest of its fields start at rest, unrotated.
struct BlockRecord {
  const std::string& name;
  int material;
  int vertexCount;
  double mass, inertia;
  std::uint8_t driven;
  double boundingRadius;
  Vec2 centroid, velocity;
  double angularVelocity;
  Vec2 force;
  double moment;
  bool deformable;
};

void appendBlock(Model& m, const BlockRecord& r) {
  Blocks& b = m.blocks;
  b.name.push_back(r.name);
  b.material.push_back(r.material);
  b.firstVertex.push_back(m.vertices.size());
  b.vertexCount.push_back(r.vertexCount);
  b.mass.push_back(r.mass);
  b.inertia.push_back(r.inertia);
  b.driven.push_back(r.driven);
  b.boundingRadius.push_back(r.boundingRadius);
  b.initialCentroid.push_back(r.centroid);
  b.centroid.push_back(r.centroid);
  b.rotation.push_back(0.0);
  b.velocity.push_back(r.velocity);
  b.angularVelocity.push_back(r.angularVelocity);
  b.force.push_back({});
  b.moment.push_back(0.0);
  b.appliedForce.push_back(r.force);
  b.appliedMoment.push_back(r.moment);
  b.deformable.push_back(r.deformable ? 1 : 0);
  b.velocityHistory.push_back(-1);
  b.inputVelocity.push_back(r.velocity);
  b.inputAngularVelocity.push_back(r.angularVelocity);
}

void addRigidBlock(Model& m, const BlockInput& in) {
  const double area = signedArea(in.polygon);
  const Vec2 c = centroid(in.polygon);
  const double density = m.blockMaterials[in.material].density;
  checkMassProperties(m, in.where, in.material, area, density * area, density * polarSecondMoment(in.polygon));
  const BlockDefinition none;
  const BlockDefinition& d = in.definition ? *in.definition : none;
  double radius = 0.0;
  for (const Vec2& p : in.polygon) radius = std::max(radius, norm(p - c));
  appendBlock(m, {in.name, in.material, static_cast<int>(in.polygon.size()), density * area,
                  density * polarSecondMoment(in.polygon), d.fix, radius, c, d.velocity, d.angularVelocity, d.force,
                  d.moment, false});
  const int block = m.blocks.size() - 1;
  for (const Vec2& p : in.polygon) {
    m.vertices.block.push_back(block);
    m.vertices.localPosition.push_back(p - c);
    m.vertices.geometry.push_back({p, {}, {}, 0.0, 0.0});
  }
}

// A deformable block: its gridpoints and zones, and an entry in Blocks (no contact vertices:
// its outline becomes them in attachDeformableOutlines).
void addDeformableBlock(Model& m, const std::string& name, int material, const Mesh& mesh) {
  const int block = m.blocks.size();
  const double density = m.blockMaterials[material].density;
  double area = 0.0;
  Vec2 moment;
  for (const auto& t : mesh.triangles) {
    const Vec2 p0 = mesh.nodes[t[0]], p1 = mesh.nodes[t[1]], p2 = mesh.nodes[t[2]];
    const double a = 0.5 * cross(p1 - p0, p2 - p0);
    area += a;
    moment += (a / 3.0) * (p0 + p1 + p2);
  }
  checkMassProperties(m, "block '" + name + "'", material, area, density * area, 0.0);
  const Vec2 c = (1.0 / area) * moment;
  double radius = 0.0;
  for (const Vec2& p : mesh.nodes) radius = std::max(radius, norm(p - c));
  // No contact vertices yet: its outline becomes them in attachDeformableOutlines.
  appendBlock(m, {name, material, 0, density * area, 0.0, 0, radius, c, {}, 0.0, {}, 0.0, true});

  Gridpoints& g = m.gridpoints;
  const int first = g.size();
  for (const Vec2& p : mesh.nodes) {
    g.block.push_back(block);
    g.initialPosition.push_back(p);
    g.position.push_back(p);
    g.velocity.push_back({});
    g.tractionForce.push_back({});
    g.driven.push_back(0);
  }
  Zones& z = m.zones;
  for (const auto& t : mesh.triangles) {
    z.gridpoint.push_back({first + t[0], first + t[1], first + t[2]});
    z.block.push_back(block);
    z.material.push_back(material);
    z.sxx.push_back(0.0);
    z.syy.push_back(0.0);
    z.sxy.push_back(0.0);
    z.szz.push_back(0.0);
    z.plasticState.push_back(Elastic);
  }
  for (const auto& [from, to] : boundaryEdges(mesh)) m.boundaryEdges.push_back({block, first + from, first + to});
  const MeshQuality q = meshQuality(mesh);
  if (q.minAngleDegrees < 1.0)
    throw GeometryError("block '" + name + "': zone " + std::to_string(q.worstTriangle) + " is a sliver (smallest angle " +
                        shown(q.minAngleDegrees) + " degrees); change the zoning (nx, ny, radial, circumferential, grading)");
}

// Refuses a zoning that would take the scene past kSceneZoneLimit, before it is made; shows a
// progress line for a large one.
void checkZoneCount(const Origin& origin, std::string_view key, double zones, const std::string& how,
                    std::size_t zonesBefore, SetupProgress& progress) {
  const double left = static_cast<double>(kSceneZoneLimit) - static_cast<double>(zonesBefore);
  if (zones > left)
    origin.fail(key, "makes " + how + " = " + shownCount(zones) + " zones, more than the " + shownCount(left) +
                         " left of the scene's limit of " + std::to_string(kSceneZoneLimit) + " zones (" +
                         std::to_string(zonesBefore) + " in the blocks before it): zone it more coarsely");
  if (zones > 2e5) progress.show("zoning " + origin.location() + ": about " + shownCount(zones) + " zones", true);
}

// The zones of a deformable block, checked against what the scene's zone limit leaves.
Mesh zoneBlock(const BlockDefinition& d, std::size_t zonesBefore, SetupProgress& progress) {
  const ZoningDefinition& z = d.zoning;
  if (z.kind == ZoningDefinition::Kind::Annulus) {
    checkZoneCount(d.origin, "annulus", 4.0 * z.annulus.radial * z.annulus.circumferential, "4 radial circumferential",
                   zonesBefore, progress);
    return inZoneOrder(crossedAnnulusMesh(z.annulus));
  }
  const Polygon& p = d.vertices;
  if (z.kind == ZoningDefinition::Kind::Unstructured) {
    // Any convex polygon, quality triangles no longer than max_edge.
    validateBlockPolygon(p, 0.0, d.origin.location());
    double perimeter = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) perimeter += norm(p[(i + 1) % p.size()] - p[i]);
    if (perimeter / z.maxEdge > 1e5) z.origin.fail("max_edge", "is too small for this block: over 1e5 edges on its outline");
    checkZoneCount(z.origin, "max_edge", kDelaunayZonesPerArea * signedArea(p) / (z.maxEdge * z.maxEdge),
                   "about 6 area / max_edge^2", zonesBefore, progress);
    return inZoneOrder(delaunayMesh(p, z.maxEdge));
  }
  if (p.size() != 4)
    d.origin.fail("zoning", "structured zoning needs a quadrilateral block (4 vertices), got " + std::to_string(p.size()));
  // Convex and counter-clockwise, like every block (edge lengths do not matter without contacts).
  validateBlockPolygon(p, 0.0, d.origin.location());
  checkZoneCount(d.origin, "zoning", 4.0 * z.nx * z.ny, "4 nx ny", zonesBefore, progress);
  return inZoneOrder(crossedQuadMesh({p[0], p[1], p[2], p[3]}, z.nx, z.ny));
}

void addMaterials(Model& m, const SceneDefinition& s) {
  for (const BlockMaterialDefinition& d : s.blockMaterials) {
    for (const BlockMaterial& other : m.blockMaterials)
      if (other.name == d.material.name) d.origin.fail("name", "block material '" + d.material.name + "' is defined twice");
    m.blockMaterials.push_back(d.material);
  }
  for (const JointMaterialDefinition& d : s.jointMaterials) {
    for (const JointMaterial& other : m.jointMaterials)
      if (other.name == d.material.name) d.origin.fail("name", "joint material '" + d.material.name + "' is defined twice");
    m.jointMaterials.push_back(d.material);
  }
  if (s.model.defaultJoint.empty()) {
    if (m.jointMaterials.size() > 1)
      s.model.origin.fail("default_joint", "is required when more than one joint material is defined");
    m.defaultJoint = m.jointMaterials.empty() ? -1 : 0;
  } else {
    m.defaultJoint = jointMaterialNamed(m, s.model.origin, "default_joint", s.model.defaultJoint);
  }
}

// Blocks, explicit and cut from regions, in input order.
std::vector<BlockInput> blockInputs(Model& m, const SceneDefinition& s) {
  std::vector<BlockInput> inputs;
  std::map<std::string, std::string> nameOrigin;
  auto claimName = [&](const Origin& origin, const std::string& name) {
    auto [it, fresh] = nameOrigin.emplace(name, origin.prefix);
    if (!fresh) origin.fail("name", "block name '" + name + "' is already used by " + it->second);
  };
  SetupProgress progress;
  std::size_t zonesSoFar = 0;
  for (const BlockDefinition& d : s.blocks) {
    BlockInput in;
    in.definition = &d;
    in.name = d.name;
    claimName(d.origin, d.name);
    in.material = blockMaterialNamed(m, d.origin, "material", d.material);
    if (d.zoning.kind != ZoningDefinition::Kind::Rigid) {
      in.mesh = zoneBlock(d, zonesSoFar, progress);
      zonesSoFar += in.mesh->triangles.size();
      if (!m.blockMaterials[in.material].elastic())
        d.origin.fail("material", "a deformable block needs an elastic material: give block material '" +
                                      m.blockMaterials[in.material].name + "' young and poisson (or bulk and shear)");
      in.where = d.origin.file + ": block '" + d.name + "' (" + d.origin.prefix + ")";
    } else {
      in.polygon = d.vertices;
      in.where = d.origin.file + ": block '" + d.name + "' (" + d.origin.prefix + ", line " +
                 std::to_string(d.origin.line) + ")";
      if (d.simplyDeformable) in.simplyDeformable = &d.origin;
    }
    inputs.push_back(std::move(in));
  }
  for (const RegionDefinition& d : s.regions) {
    const RegionSpec& region = d.region;
    const int material = blockMaterialNamed(m, d.origin, "material", d.material);
    validateBlockPolygon(region.boundary, 0.0, d.origin.file + ": region '" + region.name + "' (" + d.origin.prefix + ")");
    // Bounded before any cut: a spacing of 1e-9 or a tiny trace once ran for minutes.
    const RegionEstimate estimate = estimateRegion(region);
    const double left = static_cast<double>(kSceneBlockLimit) - static_cast<double>(inputs.size());
    if (estimate.blocks > left)
      d.origin.fail(region.jointSets.empty() ? "crack" : "joint_set",
                    "region '" + region.name + "' would be cut into up to " + shownCount(estimate.blocks) +
                        " blocks (1 + cracks + joint lines + crossings of lines of different sets, the lines counted at "
                        "spacing - spacing_variation), more than the " + shownCount(left) + " left of the scene's limit of " +
                        std::to_string(kSceneBlockLimit) + " blocks: raise the spacing of its joint sets");
    if (estimate.segments > kRegionSegmentLimit)
      d.origin.fail("joint_set", "region '" + region.name + "' would be cut with up to " + shownCount(estimate.segments) +
                                     " joint segments (per joint line, its longest chord over the shortest trace + gap), "
                                     "more than the limit of " + shownCount(kRegionSegmentLimit) + ": raise trace or gap");
    const std::string cutting = "cutting region '" + region.name + "' into up to " + shownCount(estimate.blocks) + " blocks: ";
    progress.show(cutting + "0", estimate.blocks > 1e5);
    const std::vector<Polygon> pieces =
        cutRegion(region, [&](std::size_t blocks) { progress.show(cutting + std::to_string(blocks)); });
    for (std::size_t k = 0; k < pieces.size(); ++k) {
      BlockInput in;
      in.name = region.name + "." + std::to_string(k + 1);
      claimName(d.origin, in.name);
      in.material = material;
      in.polygon = pieces[k];
      in.where = d.origin.file + ": block '" + in.name + "' cut from region '" + region.name + "' (" + d.origin.prefix + ")";
      if (d.simplyDeformable) in.simplyDeformable = &d.origin;
      inputs.push_back(std::move(in));
    }
  }
  if (inputs.empty()) s.root.fail("block", "the scene has no blocks: add [[block]] or [[region]]");
  return inputs;
}

// Excavation before the run: rigid blocks whose centroid lies in the region go, and so do the
// zones of deformable blocks whose centroid does (the outline then follows the zones left).
void excavate(std::vector<BlockInput>& inputs, const ExcavationDefinition& d) {
  const auto inside = [&d](Vec2 p) { return d.region.contains(p); };
  std::size_t removed = 0;
  std::vector<BlockInput> kept;
  for (BlockInput& in : inputs) {
    if (in.mesh) {
      const std::size_t before = in.mesh->triangles.size();
      in.mesh = withoutTriangles(*in.mesh, inside);
      removed += before - in.mesh->triangles.size();
      if (in.mesh->triangles.empty()) continue;
    } else if (inside(centroid(in.polygon))) {
      ++removed;
      continue;
    }
    kept.push_back(std::move(in));
  }
  if (removed == 0) d.origin.failTable("removes nothing: no block centroid and no zone centroid lies in it");
  if (kept.empty()) d.origin.failTable("removes every block: the scene would be empty");
  inputs = std::move(kept);
}

void checkModelWide(const Model& m, const SceneDefinition& s) {
  if (s.settings.stiffnessDamping > 0.0) {
    const char* key = s.solver.keys.count("rayleigh") ? "rayleigh" : "stiffness_damping";
    for (const JointMaterial& j : m.jointMaterials)
      if (j.law == JointLaw::ContinuouslyYielding)
        s.solver.fail(key, "damps linear joint springs; joint material '" + j.name + "' is continuously yielding");
  }
  // A weight beyond the range of a double would first show as a NaN energy, blamed on the step.
  for (int b = 0; b < m.blocks.size(); ++b)
    if (!std::isfinite(m.blocks.mass[b] * norm(m.gravity)))
      s.model.origin.fail("gravity", "its magnitude times the mass of block '" + m.blocks.name[b] + "' (" +
                                         shown(m.blocks.mass[b]) + " kg/m) is beyond the range of a double: "
                                         "lower model.gravity or the block's density");
  bool anyRigid = false;
  for (int b = 0; b < m.blocks.size(); ++b) anyRigid = anyRigid || !m.blocks.deformable[b];
  if (m.jointMaterials.empty() && (m.blocks.size() > 1 || anyRigid))
    s.root.fail("joint_material", "at least one [[joint_material]] is required when the scene has more than one block or "
                                  "a rigid block (the rigid-block time step, 1.3-28, takes the joint stiffness)");
}

// A phase's switch to local damping or its direct solve, against the run's settings and the
// model as the phase will find it.
void checkPhaseSolver(const PhaseDefinition& d, const Model& m, const RunSettings& settings, bool velocityDriven) {
  if (d.localDamping.value_or(0.0) > 0.0 && settings.stiffnessDamping > 0.0)
    d.origin.fail("local_damping", "the run has stiffness-proportional damping (solver.stiffness_damping or "
                                   "solver.rayleigh), which goes with mass damping, not with local damping");
  if (!d.staticSolve) return;
  for (int b = 0; b < m.blocks.size(); ++b)
    if (!m.blocks.deformable[b] && !m.blocks.excavated(b))
      d.origin.fail("static_solve", "the direct solve covers deformable blocks only; block '" + m.blocks.name[b] +
                                        "' is rigid");
  if (velocityDriven)
    d.origin.fail("static_solve", "a boundary condition in force when the phase starts drives gridpoints at a velocity, "
                                  "which has no static meaning; free it in this phase (free = [...]) or solve by cycling");
  for (const JointMaterial& j : m.jointMaterials)
    if (j.law == JointLaw::ContinuouslyYielding)
      d.origin.fail("static_solve", "the direct solve takes joints as linear springs, and joint material '" + j.name +
                                        "' is continuously yielding; relax the phase with explicit cycles instead");
}

void applyInitialStress(Model& m, const InitialStressDefinition& d, bool farField) {
  if (m.zones.size() == 0 && !farField)
    d.origin.failTable("needs deformable blocks (it sets the stress of zones) or a far field (whose edges on rigid "
                       "blocks hold it)");
  const auto& s = d.stress;
  const auto &gx = d.gradientX, &gy = d.gradientY;
  for (int z = 0; z < m.zones.size(); ++z) {
    const auto& n = m.zones.gridpoint[z];
    const Vec2 c = (1.0 / 3.0) * (m.gridpoints.position[n[0]] + m.gridpoints.position[n[1]] + m.gridpoints.position[n[2]]);
    m.zones.sxx[z] = s[0] + gx[0] * c.x + gy[0] * c.y;
    m.zones.syy[z] = s[1] + gx[1] * c.x + gy[1] * c.y;
    m.zones.sxy[z] = s[2] + gx[2] * c.x + gy[2] * c.y;
    m.zones.szz[z] = s[3] + gx[3] * c.x + gy[3] * c.y;
  }
}

InitialWave initialWave(const Model& m, const InitialWaveDefinition& d) {
  if (m.zones.size() == 0) d.origin.failTable("needs deformable blocks: the wave lives in their zones and gridpoints");
  InitialWave w;
  w.shear = d.shear;
  const double a = radians(d.directionDegrees);
  w.direction = {std::cos(a), std::sin(a)};
  w.centre = d.centre;
  w.amplitude = d.amplitude;
  w.width = d.width;
  w.frontWidth = d.frontWidth;
  if (!d.block.empty()) {
    w.block = blockNamed(m, d.origin, "block", d.block);
    if (!m.blocks.deformable[w.block])
      d.origin.fail("block", "block '" + d.block + "' is rigid: an initial wave lives in deformable blocks");
  }
  return w;
}

void assignJoint(Model& m, const JointAssignmentDefinition& d) {
  const int a = blockNamed(m, d.origin, "blocks", d.blocks[0]), b = blockNamed(m, d.origin, "blocks", d.blocks[1]);
  const int index = jointMaterialNamed(m, d.origin, "joint", d.joint);
  const std::pair<int, int> pair{std::min(a, b), std::max(a, b)};
  if (a == b) d.origin.fail("blocks", "a joint is between two different blocks");
  for (const auto& [assigned, material] : m.jointAssignments)
    if (assigned == pair)
      d.origin.fail("blocks", "the joint between '" + d.blocks[0] + "' and '" + d.blocks[1] + "' is already assigned ('" +
                                  m.jointMaterials[material].name + "')");
  m.jointAssignments.push_back({pair, index});
}

// What simply-deformable blocks do not take: loads that act on a rigid block's force and moment
// alone would leave their strains without them.
void checkStrainModeScene(const Model& m, const SceneDefinition& s, const Origin& origin) {
  // A phase's new Mohr-Coulomb strength would make nothing of a simply-deformable block.
  for (const PhaseDefinition& p : s.phases)
    for (const BlockStrengthDefinition& d : p.blockStrengths)
      for (int k = 0; k < m.strainModes.size(); ++k)
        if (m.blockMaterials[m.blocks.material[m.strainModes.block[k]]].name == d.material)
          d.origin.fail("name", "block material '" + d.material + "' is that of simply-deformable block '" +
                                    m.blocks.name[m.strainModes.block[k]] + "', which is elastic: a Mohr-Coulomb "
                                    "strength applies to zones");
  auto anyPhase = [&s](auto has) { return std::any_of(s.phases.begin(), s.phases.end(), has); };
  std::string what;
  if (m.flow.present) what = "fluid pressures in the joints ([fluid])";
  else if (s.boundaryElements || anyPhase([](const PhaseDefinition& p) { return p.boundaryElements.has_value(); }))
    what = "a boundary-element far field";
  else if (!s.beams.empty() || !s.cables.empty() || !s.bolts.empty() ||
           anyPhase([](const PhaseDefinition& p) { return !p.beams.empty() || !p.cables.empty() || !p.bolts.empty(); }))
    what = "beams, cables or bolts";
  if (!what.empty())
    origin.fail("kind", "simply-deformable blocks take the loads of contacts, gravity, block forces and moments and "
                        "boundary velocities; this scene also has " + what + ", which act on a block's rigid motion "
                        "alone and would leave its strain without them: make the block rigid or zone it");
}

HistorySpec buildHistory(const Model& m, const HistoryDefinition& d, const std::vector<Phase>& phases) {
  HistorySpec h;
  h.name = d.name;
  const auto info = findHistoryQuantity(d.quantity);
  if (!info) d.origin.fail("quantity", "unknown quantity '" + d.quantity + "'; known: " + historyQuantityNames());
  h.quantity = info->quantity;
  const bool zoneMean = h.quantity == HistoryQuantity::MeanSxx || h.quantity == HistoryQuantity::MeanSyy ||
                        h.quantity == HistoryQuantity::MeanSxy;
  if (zoneMean && m.zones.size() == 0)
    d.origin.fail("quantity", d.quantity + " averages the stress of the zones, and the scene has no deformable block");
  const bool thermal = h.quantity == HistoryQuantity::GridpointTemperature || h.quantity == HistoryQuantity::HeatTime ||
                       h.quantity == HistoryQuantity::HeatStored || h.quantity == HistoryQuantity::HeatSources ||
                       h.quantity == HistoryQuantity::HeatBoundary || h.quantity == HistoryQuantity::HeatFixed ||
                       h.quantity == HistoryQuantity::HeatFlow;
  if (thermal && !m.heat.on)
    d.origin.fail("quantity", d.quantity + " is a heat-conduction quantity, and the scene has no [heat] table");
  if (info->subject == HistorySubject::Block) {
    h.block = blockNamed(m, d.origin, "block", d.block);
    if (m.blocks.deformable[h.block])
      d.origin.fail("block", "block '" + m.blocks.name[h.block] + "' is deformable: its motion is its gridpoints'; use "
                             "gridpoint.* or zone.* quantities with a point");
    const bool strain = h.quantity >= HistoryQuantity::BlockSxx && h.quantity <= HistoryQuantity::BlockExy;
    if (strain && !m.strainModes.holds(h.block))
      d.origin.fail("block", "block '" + m.blocks.name[h.block] + "' is rigid: " + d.quantity + " is the stress or strain "
                             "of a simply-deformable block (kind = \"simply-deformable\")");
  } else if (info->subject == HistorySubject::Fluid) {
    if (!m.flow.present) d.origin.fail("quantity", d.quantity + " is a fluid-flow quantity, and the scene has no [fluid] table");
    if (d.point) h.point = *d.point;
  } else if (info->subject == HistorySubject::Beam) {
    const Structures& st = m.structures;
    const int beam = beamNamed(m, d.origin, d.beam);
    const Beam& b = st.beams[beam];
    h.point = *d.point;
    auto distance = [&](int e) {
      const Vec2 p = st.nodes.initialPosition[st.elements.node[e][0]], q = st.nodes.initialPosition[st.elements.node[e][1]];
      const double t = std::clamp(dot(h.point - p, q - p) / dot(q - p, q - p), 0.0, 1.0);
      return norm(h.point - (p + t * (q - p)));
    };
    h.beamNode = nearestBeamNode(m, beam, h.point);
    h.beamElement = b.firstElement;
    for (int e = b.firstElement; e < b.firstElement + b.elementCount; ++e)
      if (distance(e) < distance(h.beamElement)) h.beamElement = e;
  } else if (info->subject == HistorySubject::Cable) {
    const Structures& st = m.structures;
    const int cable = cableNamed(m, d.origin, d.cable);
    const Cable& c = st.cables[cable];
    h.point = *d.point;
    h.cableNode = nearestCableNode(m, cable, h.point);
    h.cableElement = c.firstElement;
    auto mid = [&](int e) {
      return 0.5 * (st.cableNodes.position[st.cableElements.node[e][0]] + st.cableNodes.position[st.cableElements.node[e][1]]);
    };
    for (int e = c.firstElement; e < c.firstElement + c.elementCount; ++e)
      if (norm(mid(e) - h.point) < norm(mid(h.cableElement) - h.point)) h.cableElement = e;
  } else if (info->subject == HistorySubject::Bolt) {
    const std::vector<Bolt>& bolts = m.structures.bolts;
    for (int i = 0; i < static_cast<int>(bolts.size()); ++i)
      if (bolts[i].name == d.bolt) h.bolt = i;
    if (h.bolt < 0) d.origin.fail("bolt", "no [[bolt]] or [[phase.bolt]] is named '" + d.bolt + "'");
    h.point = *d.point;
  } else if (info->subject == HistorySubject::Line) {
    if (!(norm(d.to - d.from) > 0.0)) d.origin.fail("to", "is the point `from`: a line needs two distinct ends");
    h.point = d.from;
    h.lineEnd = d.to;
    h.line = heatLine(m, d.from, d.to);
    if (h.line.edge.empty())
      d.origin.fail("from", "the segment from (" + shown(d.from.x) + ", " + shown(d.from.y) + ") to (" + shown(d.to.x) + ", " +
                                shown(d.to.y) + ") runs along no zone edge: heat.flow sums the flux through the zones' edges "
                                "that lie on it, so give ends on a line of the zoning (a block's side, a row of gridpoints)");
  } else if (info->subject == HistorySubject::Joint) {
    h.block = blockNamed(m, d.origin, "blocks", d.blocks[0]);
    h.otherBlock = blockNamed(m, d.origin, "blocks", d.blocks[1]);
    if (h.block == h.otherBlock) d.origin.fail("blocks", "a joint is between two different blocks");
  } else if (info->subject == HistorySubject::Gridpoint || info->subject == HistorySubject::Zone) {
    h.block = blockNamed(m, d.origin, "block", d.block);
    if (!m.blocks.deformable[h.block])
      d.origin.fail("block", "block '" + m.blocks.name[h.block] + "' is rigid: " + std::string(info->name) +
                                 " needs a deformable block; use block.* quantities for a rigid block");
    if (!d.point) d.origin.fail("point", "is required");
    if (info->subject == HistorySubject::Gridpoint) h.gridpoint = nearestGridpoint(m, h.block, *d.point);
    else h.zone = zoneAt(m, h.block, *d.point);
    if (h.gridpoint < 0 && h.zone < 0)
      d.origin.fail("point", "is not inside block '" + m.blocks.name[h.block] +
                                 "': a zone history samples the zone that holds the point");
  }
  h.every = d.every;
  // A zone a phase will excavate (at the positions the scene gives) cannot be sampled after it.
  if (h.zone >= 0) {
    const auto& n = m.zones.gridpoint[h.zone];
    const Vec2 c = (1.0 / 3.0) * (m.gridpoints.position[n[0]] + m.gridpoints.position[n[1]] + m.gridpoints.position[n[2]]);
    for (const Phase& phase : phases)
      for (const ExcavationRegion& region : phase.changes.excavations)
        if (region.contains(c))
          d.origin.fail("point", "lies in a zone that " + region.where + " of phase '" + phase.name +
                                     "' excavates; give the history a point in a zone that stays");
  }
  return h;
}

}  // namespace

int blockNamed(const Model& m, const Origin& origin, std::string_view key, const std::string& name) {
  for (int b = 0; b < m.blocks.size(); ++b)
    if (m.blocks.name[b] == name) return b;
  origin.fail(key, "no block named '" + name + "'");
}

int blockMaterialNamed(const Model& m, const Origin& origin, std::string_view key, const std::string& name) {
  for (std::size_t i = 0; i < m.blockMaterials.size(); ++i)
    if (m.blockMaterials[i].name == name) return static_cast<int>(i);
  origin.fail(key, "no block material named '" + name + "'");
}

int jointMaterialNamed(const Model& m, const Origin& origin, std::string_view key, const std::string& name) {
  for (std::size_t i = 0; i < m.jointMaterials.size(); ++i)
    if (m.jointMaterials[i].name == name) return static_cast<int>(i);
  origin.fail(key, "no joint material named '" + name + "'");
}

Scene buildScene(SceneDefinition s) {
  Scene scene;
  scene.title = s.title;
  scene.warnings = std::move(s.warnings);
  scene.settings = s.settings;
  Model& m = scene.model;
  m.gravity = s.model.gravity;
  m.roundingLength = s.model.rounding;
  m.contactTolerance = s.model.contactTolerance > 0.0 ? s.model.contactTolerance : s.model.rounding;
  addMaterials(m, s);

  std::vector<BlockInput> inputs = blockInputs(m, s);
  for (const ExcavationDefinition& d : s.excavations) excavate(inputs, d);
  std::vector<std::pair<int, const Origin*>> strained;  // the simply-deformable blocks
  for (const BlockInput& in : inputs) {
    if (in.mesh) {
      addDeformableBlock(m, in.name, in.material, *in.mesh);
      continue;
    }
    validateBlockPolygon(in.polygon, m.roundingLength, in.where);
    addRigidBlock(m, in);
    if (in.simplyDeformable) {
      if (!m.blockMaterials[in.material].elastic())
        in.simplyDeformable->fail("material", "a simply-deformable block strains elastically: give block material '" +
                                                  m.blockMaterials[in.material].name + "' young and poisson (or bulk and shear)");
      if (m.blockMaterials[in.material].plastic)
        in.simplyDeformable->fail("material", "a simply-deformable block is elastic, and block material '" +
                                                  m.blockMaterials[in.material].name + "' has a Mohr-Coulomb strength, "
                                                  "which applies to zones: zone the block, or give it an elastic material");
      strained.emplace_back(m.blocks.size() - 1, in.simplyDeformable);
    }
    if (in.definition && in.definition->velocityHistory) {
      m.timeFunctions.push_back(*in.definition->velocityHistory);
      m.blocks.velocityHistory.back() = static_cast<int>(m.timeFunctions.size()) - 1;
    }
  }
  checkModelWide(m, s);
  if (m.blocks.size() > 1) attachDeformableOutlines(m);
  computeBoundaryGeometry(m);
  for (const auto& [block, origin] : strained) addStrainModes(m, block);
  for (int b = 0; b < m.blocks.size(); ++b) placeBlockVertices(m, b);
  addFluid(m, s);
  addStructures(m, s);

  for (const BoundaryDefinition& d : s.boundaries) {
    BoundaryCondition condition = resolveBoundary(d, m);
    for (const BoundaryCondition& other : m.boundaryConditions)
      if (!condition.name.empty() && other.name == condition.name)
        d.origin.fail("name", "boundary '" + condition.name + "' is defined twice");
    addBoundaryCondition(m, std::move(condition), 0.0);
  }
  // Phases after the boundaries: a phase's boundary conditions select the model's gridpoints,
  // and may free only conditions active when the phase starts.
  std::set<std::string> active;
  for (const BoundaryCondition& b : m.boundaryConditions)
    if (!b.name.empty()) active.insert(b.name);
  for (const FlowBoundaryDefinition& d : s.flowBoundaries)
    if (!d.boundary.name.empty() && !active.insert(d.boundary.name).second)
      d.origin.fail("name", "flow boundary '" + d.boundary.name + "' has the name of a [[boundary]]: give it another "
                            "(a phase's free takes either kind by name)");
  for (const BeamDefinition& d : s.beams)
    if (!active.insert(d.name).second)
      d.origin.fail("name", "beam '" + d.name + "' has the name of a boundary: give it another (a phase's free takes "
                            "boundaries and supports by name)");
  for (const CableDefinition& d : s.cables)
    if (!active.insert(d.name).second)
      d.origin.fail("name", "cable '" + d.name + "' has the name of a boundary or beam: give it another (a phase's free "
                            "takes boundaries and supports by name)");
  for (const BoltDefinition& d : s.bolts)
    if (!active.insert(d.name).second)
      d.origin.fail("name", "bolt '" + d.name + "' has the name of a boundary, beam or cable: give it another (a phase's "
                            "free takes boundaries and supports by name)");
  std::optional<Model> excavated;  // a copy of the model, excavated as the phases will, once one does
  // Boundary conditions in force, by name ("" for unnamed ones), and whether they drive a velocity.
  std::vector<std::pair<std::string, bool>> inForce;
  for (const BoundaryCondition& b : m.boundaryConditions) inForce.emplace_back(b.name, b.velocityBits != 0);
  bool farField = false;  // an earlier phase's
  for (const PhaseDefinition& d : s.phases) {
    for (const Phase& before : scene.settings.phases)
      if (before.name == d.name) d.origin.fail("name", "phase '" + d.name + "' is defined twice");
    scene.settings.phases.push_back(buildPhase(d, m, excavated, active));
    const PhaseChanges& changes = scene.settings.phases.back().changes;
    if (changes.boundaryElements && (s.boundaryElements || farField))
      d.boundaryElements->origin.failTable("puts a far field in place, and one is already there (the scene's "
                                           "[boundary_elements] or an earlier phase's): a model has one");
    farField = farField || changes.boundaryElements.has_value();
    for (const std::string& name : changes.freeBoundaries)
      std::erase_if(inForce, [&name](const auto& b) { return b.first == name; });
    for (const BoundaryCondition& b : changes.boundaries) inForce.emplace_back(b.name, b.velocityBits != 0);
    bool velocityDriven = false;
    for (const auto& [name, drives] : inForce) velocityDriven = velocityDriven || drives;
    checkPhaseSolver(d, excavated ? *excavated : m, s.settings, velocityDriven);
  }
  if (s.initialStress) applyInitialStress(m, *s.initialStress, s.boundaryElements || farField);
  if (s.boundaryElements) {
    m.boundaryElements = boundaryElementField(m, *s.boundaryElements);
    if (s.initialStress) holdInSitu(m.boundaryElements, *s.initialStress);
    holdPresentStress(m);
  }
  for (Phase& phase : scene.settings.phases)
    if (phase.changes.boundaryElements && s.initialStress) holdInSitu(*phase.changes.boundaryElements, *s.initialStress);
  for (const InitialWaveDefinition& d : s.initialWaves) m.initialWaves.push_back(initialWave(m, d));
  for (const JointAssignmentDefinition& d : s.jointAssignments) assignJoint(m, d);
  if (s.heat) {
    buildHeat(m, s);
    if (!s.phases.empty() && s.heat->time > 0.0)
      s.heat->origin.fail("time", "is the thermal time of a run without phases; with [[phase]] give each phase its heat_time");
    scene.settings.heatTime = s.heat->time;
  } else if (!s.heatBoundaries.empty() || !s.heatSources.empty()) {
    const Origin& o = s.heatBoundaries.empty() ? s.heatSources.front().origin : s.heatBoundaries.front().origin;
    o.failTable("needs a [heat] table: it sets the thermal solution this acts on");
  }
  for (std::size_t k = 0; k < s.phases.size(); ++k) {
    const PhaseDefinition& d = s.phases[k];
    if (d.heatTime && !s.heat) d.origin.fail("heat_time", "needs a [heat] table");
    if (s.heat && !d.excavations.empty())
      d.excavations.front().origin.failTable("a phase cannot excavate a model that conducts heat ([heat]): the thermal "
                                             "nodes are formed once; excavate before the run with [[excavation]]");
    scene.settings.phases[k].changes.heatTime = d.heatTime.value_or(0.0);
  }
  if (!strained.empty()) checkStrainModeScene(m, s, *strained.front().second);
  std::set<std::string> historyNames;
  for (const HistoryDefinition& d : s.histories) {
    if (!historyNames.insert(d.name).second) d.origin.fail("name", "history '" + d.name + "' is defined twice");
    scene.histories.push_back(buildHistory(m, d, scene.settings.phases));
  }
  return scene;
}

}  // namespace vdec
