// [[beam_material]], [[beam]], [[beam_node]], [[cable_material]], [[cable]], [[cable_node]],
// [[bolt_material]], [[bolt]]: rock support (docs/models/support.md).
#include <cmath>
#include <numbers>
#include <tuple>
#include <utility>

#include "core/shown.hpp"
#include "io/scene_sections.hpp"

namespace vdec {

namespace {

constexpr int kMostElements = 1000000;

BeamMaterialDefinition readBeamMaterial(TableReader& r) {
  BeamMaterialDefinition d;
  d.origin = r.origin();
  BeamMaterial& m = d.material;
  m.name = r.string("name");
  m.young = r.positive("young");
  m.area = r.positive("area");
  m.inertia = r.positive("inertia");
  m.density = r.positive("density");
  d.spacing = r.has("spacing") ? r.positive("spacing") : 1.0;
  m.tieNormalStiffness = r.nonNegative("tie_normal_stiffness", 0.0);
  m.tieShearStiffness = r.nonNegative("tie_shear_stiffness", 0.0);
  if (r.has("tie_cohesion")) m.tieCohesion = r.nonNegative("tie_cohesion", 0.0);
  m.tieFriction = std::tan(radians(r.angleDegrees("tie_friction", 0.0)));
  if (r.has("tie_tension")) m.tieTension = r.nonNegative("tie_tension", 0.0);
  if (r.has("tie_friction") && !r.has("tie_cohesion"))
    r.fail("tie_friction", "limits the ties' shear with tie_cohesion: give tie_cohesion too (0 for friction alone)");
  r.finish();
  return d;
}

CableMaterialDefinition readCableMaterial(TableReader& r) {
  CableMaterialDefinition d;
  d.origin = r.origin();
  CableMaterial& m = d.material;
  m.name = r.string("name");
  m.young = r.positive("young");
  m.area = r.positive("area");
  m.density = r.positive("density");
  d.spacing = r.has("spacing") ? r.positive("spacing") : 1.0;
  if (r.has("yield_tension")) m.yieldTension = r.positive("yield_tension");
  if (r.has("yield_compression")) m.yieldCompression = r.nonNegative("yield_compression", 0.0);
  // Either the grout's spring-slider directly, or from the annulus (1.4-42 to 1.4-44): a diameter D,
  // a grout thickness t, the grout's shear modulus (K_bond = 2 pi G / ln(1 + 2t/D)) and peak shear
  // strength (S_bond = pi (D + 2t) tau_peak).
  const bool annulus = r.has("grout_shear_modulus") || r.has("grout_shear_strength");
  if (annulus) {
    for (const char* key : {"bond_stiffness", "bond_strength"})
      if (r.has(key)) r.fail(key, "give the grout either as bond_stiffness and bond_strength or by its annulus (diameter, grout_thickness, grout_shear_modulus, grout_shear_strength), not both");
    const double diameter = r.positive("diameter"), thickness = r.positive("grout_thickness");
    m.bondStiffness = 2.0 * std::numbers::pi * r.positive("grout_shear_modulus") / std::log(1.0 + 2.0 * thickness / diameter);
    if (r.has("grout_shear_strength"))
      m.bondStrength = std::numbers::pi * (diameter + 2.0 * thickness) * r.positive("grout_shear_strength");
  } else {
    for (const char* key : {"diameter", "grout_thickness"})
      if (r.has(key)) r.fail(key, "describes the grout's annulus: give grout_shear_modulus too (or leave it out)");
    m.bondStiffness = r.positive("bond_stiffness");
    if (r.has("bond_strength")) m.bondStrength = r.positive("bond_strength");
  }
  r.finish();
  return d;
}

BoltMaterialDefinition readBoltMaterial(TableReader& r) {
  BoltMaterialDefinition d;
  d.origin = r.origin();
  BoltMaterial& m = d.material;
  m.name = r.string("name");
  m.axialStiffness = r.positive("axial_stiffness");
  m.shearStiffness = r.nonNegative("shear_stiffness", 0.0);
  if (!r.has("shear_stiffness")) r.fail("shear_stiffness", "is required (0 for a bolt that only acts along its axis)");
  if (r.has("axial_strength")) m.axialStrength = r.positive("axial_strength");
  if (r.has("shear_strength")) m.shearStrength = r.positive("shear_strength");
  m.activeLength = r.positive("active_length");
  m.crushing = r.boolean("crushing", true);
  d.spacing = r.has("spacing") ? r.positive("spacing") : 1.0;
  r.finish();
  return d;
}

// A straight support's two ends (`points`), distinct.
std::pair<Vec2, Vec2> readSegment(TableReader& r, const std::string& what) {
  const Polygon points = r.polygon("points");
  if (points.size() != 2) r.fail("points", "a " + what + " is straight: give its two ends, [[x0, y0], [x1, y1]]");
  if (points[0].x == points[1].x && points[0].y == points[1].y) r.fail("points", "the two ends are the same point");
  return {points[0], points[1]};
}

}  // namespace

BoltDefinition readBolt(TableReader& r) {
  BoltDefinition d;
  d.origin = r.origin();
  d.name = r.string("name");
  d.material = r.string("material");
  std::tie(d.from, d.to) = readSegment(r, "bolt");
  r.finish();
  return d;
}

CableDefinition readCable(TableReader& r) {
  CableDefinition d;
  d.origin = r.origin();
  d.name = r.string("name");
  d.material = r.string("material");
  std::tie(d.from, d.to) = readSegment(r, "cable");
  d.elements = static_cast<int>(r.integer("elements", 1, kMostElements));
  const double length = norm(d.to - d.from);
  d.freeLength = r.nonNegative("free_length", 0.0);
  if (!(d.freeLength < length)) r.fail("free_length", "must be shorter than the cable (" + shown(length) + " m): some of it must be grouted");
  d.head = r.boolean("head", false);
  d.pretension = r.nonNegative("pretension", 0.0);
  if (d.pretension > 0.0 && !(d.head && d.freeLength > 0.0))
    r.fail("pretension", "is held between the head plate and the grouted anchor: give head = true and a free_length > 0");
  r.finish();
  return d;
}

namespace {

CableNodeDefinition readCableNode(TableReader& r) {
  CableNodeDefinition d;
  d.origin = r.origin();
  d.cable = r.string("cable");
  d.point = r.vec2("point");
  d.force = r.number("force", 0.0);
  d.fix = r.boolean("fix", false);
  if (!r.has("force") && !r.has("fix")) r.failTable("gives the node nothing: give force (N per m, along the cable) or fix = true");
  r.finish();
  return d;
}

}  // namespace

BeamDefinition readBeam(TableReader& r) {
  BeamDefinition d;
  d.origin = r.origin();
  d.name = r.string("name");
  d.material = r.string("material");
  if (r.has("points") == r.has("arc"))
    r.failTable("give the beam's shape as points = [[x, y], ...] (a polyline) or as arc = {...}, one of the two");
  if (r.has("points")) {
    d.points = r.polygon("points");
    d.closed = r.boolean("closed", false);
    if (d.points.size() < 2) r.fail("points", "needs at least two points");
    for (std::size_t i = 0; i + 1 < d.points.size(); ++i)
      if (d.points[i].x == d.points[i + 1].x && d.points[i].y == d.points[i + 1].y) r.fail("points", "point " + std::to_string(i + 1) + " repeats the one before it");
    if (d.closed && d.points.size() < 3) r.fail("closed", "a closed beam needs at least three points");
    if (d.closed && d.points.front().x == d.points.back().x && d.points.front().y == d.points.back().y)
      r.fail("points", "of a closed beam: do not repeat the first point at the end (closed = true joins them)");
    d.elements = static_cast<int>(r.integer("elements", 1, kMostElements));
  } else {
    if (r.has("closed")) r.fail("closed", "an arc is closed when it turns through 360 degrees; remove `closed`");
    auto t = r.subtable("arc");
    const Vec2 centre = t->vec2("centre");
    const double radius = t->positive("radius");
    const double from = t->number("from"), to = t->number("to");
    if (!(to > from) || to - from > 360.0) t->fail("to", "must exceed `from` by at most 360 degrees");
    d.elements = static_cast<int>(t->integer("elements", 1, kMostElements));
    d.closed = to - from == 360.0;
    if (d.closed && d.elements < 3) t->fail("elements", "a full ring needs at least 3 elements");
    const int points = d.closed ? d.elements : d.elements + 1;
    for (int i = 0; i < points; ++i) {
      const double a = radians(from + (to - from) * i / d.elements);
      d.points.push_back(centre + radius * Vec2{std::cos(a), std::sin(a)});
    }
    t->finish();
    d.elements = 1;  // the arc's points are its nodes
  }
  d.tied = r.boolean("tied", false);
  if (r.has("load")) d.load = r.vec2("load");
  r.finish();
  return d;
}

BeamNodeDefinition readBeamNode(TableReader& r) {
  BeamNodeDefinition d;
  d.origin = r.origin();
  d.beam = r.string("beam");
  d.point = r.vec2("point");
  if (r.has("force")) d.force = r.vec2("force");
  d.moment = r.number("moment", 0.0);
  if (r.has("fix")) d.fix = degreesOfFreedom(r, "fix");
  if (!r.has("force") && !r.has("moment") && !r.has("fix"))
    r.failTable("gives the node nothing: give force = [fx, fy], moment or fix = [\"x\", \"y\", \"rotation\"]");
  r.finish();
  return d;
}

void readStructures(TableReader& top, SceneDefinition& scene) {
  for (auto [table, prefix] : top.tables("beam_material")) {
    TableReader r(*table, prefix, top.file());
    scene.beamMaterials.push_back(readBeamMaterial(r));
  }
  for (auto [table, prefix] : top.tables("beam")) {
    TableReader r(*table, prefix, top.file());
    scene.beams.push_back(readBeam(r));
  }
  for (auto [table, prefix] : top.tables("beam_node")) {
    TableReader r(*table, prefix, top.file());
    scene.beamNodes.push_back(readBeamNode(r));
  }
  for (auto [table, prefix] : top.tables("cable_material")) {
    TableReader r(*table, prefix, top.file());
    scene.cableMaterials.push_back(readCableMaterial(r));
  }
  for (auto [table, prefix] : top.tables("cable")) {
    TableReader r(*table, prefix, top.file());
    scene.cables.push_back(readCable(r));
  }
  for (auto [table, prefix] : top.tables("cable_node")) {
    TableReader r(*table, prefix, top.file());
    scene.cableNodes.push_back(readCableNode(r));
  }
  for (auto [table, prefix] : top.tables("bolt_material")) {
    TableReader r(*table, prefix, top.file());
    scene.boltMaterials.push_back(readBoltMaterial(r));
  }
  for (auto [table, prefix] : top.tables("bolt")) {
    TableReader r(*table, prefix, top.file());
    scene.bolts.push_back(readBolt(r));
  }
}

}  // namespace vdec
