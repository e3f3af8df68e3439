// [[block]], [[region]] and [[excavation]].
#include <algorithm>
#include <cmath>
#include <numbers>

#include "io/scene_sections.hpp"

namespace vdec {

namespace {

int positiveCount(TableReader& r, std::string_view key, int limit) { return static_cast<int>(r.integer(key, 1, limit)); }

}  // namespace

std::uint8_t degreesOfFreedom(TableReader& r, std::string_view key) {
  std::uint8_t bits = 0;
  for (const std::string& dof : r.strings(key)) {
    const std::uint8_t bit = dof == "x" ? DriveX : dof == "y" ? DriveY : dof == "rotation" ? DriveRotation : 0;
    if (!bit) r.fail(key, "unknown degree of freedom '" + dof + "'; use \"x\", \"y\" or \"rotation\"");
    bits |= bit;
  }
  return bits;
}

namespace {

// `annulus = {...}` (then the block has no `vertices`), or `zoning = {...}` on the block's
// polygon; Rigid without either.
ZoningDefinition readZoning(TableReader& r) {
  ZoningDefinition z;
  if (r.has("annulus")) {
    if (r.has("vertices")) r.fail("vertices", "an annulus block takes its outline from `annulus`; remove `vertices`");
    if (r.has("zoning")) r.fail("zoning", "an annulus block is zoned by its `annulus` table; remove `zoning`");
    auto t = r.subtable("annulus");
    if (!t) r.fail("annulus", "must be a table");
    z.kind = ZoningDefinition::Kind::Annulus;
    z.origin = t->origin();
    AnnulusSpec& s = z.annulus;
    s.centre = t->vec2("centre", {0.0, 0.0});
    s.inner = t->positive("inner");
    s.outer = t->positive("outer");
    if (s.outer <= s.inner) t->fail("outer", "must be larger than inner");
    const double from = t->number("from", 0.0), to = t->number("to", 90.0);
    if (!(to > from && to - from <= 360.0)) t->fail("to", "must be above `from` by at most 360 degrees");
    if (to - from >= 360.0) t->fail("to", "a full ring is not one block: use two half rings or less");
    s.angle0 = from * std::numbers::pi / 180.0;
    s.angle1 = to * std::numbers::pi / 180.0;
    s.radial = positiveCount(*t, "radial", 4096);
    s.circumferential = positiveCount(*t, "circumferential", 4096);
    s.grading = t->number("grading", 1.0);
    if (!(s.grading >= 0.2 && s.grading <= 5.0)) t->fail("grading", "must be in [0.2, 5], got " + shown(s.grading));
    t->finish();
    return z;
  }
  if (!r.has("zoning")) return z;
  auto t = r.subtable("zoning");
  if (!t) r.fail("zoning", "must be a table, e.g. zoning = { nx = 8, ny = 4 }");
  z.origin = t->origin();
  if (t->has("max_edge")) {
    z.kind = ZoningDefinition::Kind::Unstructured;
    z.maxEdge = t->positive("max_edge");
    if (t->has("nx") || t->has("ny")) t->fail("max_edge", "give either max_edge (unstructured) or nx and ny (structured)");
  } else {
    z.kind = ZoningDefinition::Kind::Structured;
    z.nx = positiveCount(*t, "nx", 4096);
    z.ny = positiveCount(*t, "ny", 4096);
  }
  t->finish();
  return z;
}

// kind = "rigid" (the default) or "simply-deformable".
bool readKind(TableReader& r) {
  const std::string kind = r.string("kind", "rigid");
  if (kind != "rigid" && kind != "simply-deformable")
    r.fail("kind", "unknown block kind '" + kind + "': \"rigid\" or \"simply-deformable\" (a block with zoning is "
                   "fully deformable)");
  return kind == "simply-deformable";
}

BlockDefinition readBlock(TableReader& r) {
  BlockDefinition d;
  d.origin = r.origin();
  d.name = r.string("name");
  d.material = r.string("material");
  d.zoning = readZoning(r);
  if (d.zoning.kind != ZoningDefinition::Kind::Annulus) d.vertices = r.polygon("vertices");
  if (r.has("kind") && d.zoning.kind != ZoningDefinition::Kind::Rigid)
    r.fail("kind", "a zoned block is fully deformable: give kind to a block without zoning (or remove the zoning)");
  d.simplyDeformable = readKind(r);
  if (d.zoning.kind != ZoningDefinition::Kind::Rigid) {
    for (const char* key : {"fix", "velocity", "angular_velocity", "force", "moment", "velocity_history"})
      if (r.has(key)) r.fail(key, "a deformable block is loaded and held through [[boundary]] tables, not block keys");
    return d;
  }
  if (r.has("fix")) d.fix = degreesOfFreedom(r, "fix");
  d.velocity = r.vec2("velocity", {0.0, 0.0});
  d.angularVelocity = r.number("angular_velocity", 0.0);
  d.force = r.vec2("force", {0.0, 0.0});
  d.moment = r.number("moment", 0.0);
  if (r.has("velocity_history")) {
    if (!d.fix)
      r.fail("velocity_history", "scales the velocity of fixed degrees of freedom, and block '" + d.name +
                                     "' has none: add fix = [\"x\"] (or y, rotation)");
    d.velocityHistory = readTimeFunction(r, "velocity_history");
  }
  return d;
}

RegionDefinition readRegion(TableReader& r) {
  RegionDefinition d;
  d.origin = r.origin();
  RegionSpec& region = d.region;
  region.name = r.string("name");
  d.material = r.string("material");
  region.boundary = r.polygon("vertices");
  d.simplyDeformable = readKind(r);
  if (r.has("seed")) {
    const long long seed = r.integer("seed");
    if (seed < 0) r.fail("seed", "must be >= 0");
    region.seed = static_cast<std::uint64_t>(seed);
  }
  for (auto [ct, cp] : r.tables("crack")) {
    TableReader c(*ct, cp, r.file());
    region.cracks.push_back({c.vec2("from"), c.vec2("to")});
    c.finish();
  }
  for (auto [jt, jp] : r.tables("joint_set")) {
    TableReader j(*jt, jp, r.file());
    JointSetSpec s;
    s.angleDeg = j.number("angle");
    // A direction: beyond a turn either way the number only loses the digits that place it.
    if (!(std::abs(s.angleDeg) <= 360.0)) j.fail("angle", "must be in [-360, 360] degrees, got " + shown(s.angleDeg));
    s.angleVariationDeg = j.nonNegative("angle_variation", 0.0);
    if (!(s.angleVariationDeg <= 90.0))
      j.fail("angle_variation", "must be in [0, 90] degrees, got " + shown(s.angleVariationDeg));
    s.spacing = j.positive("spacing");
    s.spacingVariation = j.nonNegative("spacing_variation", 0.0);
    if (s.spacingVariation >= s.spacing) j.fail("spacing_variation", "must be less than spacing");
    s.trace = j.has("trace") ? j.positive("trace") : 0.0;
    s.traceVariation = j.nonNegative("trace_variation", 0.0);
    if (s.traceVariation > 0 && s.traceVariation >= s.trace)
      j.fail("trace_variation", "must be less than trace (and trace must be set)");
    s.gap = j.nonNegative("gap", 0.0);
    s.gapVariation = j.nonNegative("gap_variation", 0.0);
    if (s.gapVariation > s.gap) j.fail("gap_variation", "must not exceed gap");
    if (s.gap > 0 && s.trace <= 0) j.fail("gap", "a gap needs a finite trace length");
    s.origin = j.vec2("origin", {0.0, 0.0});
    // The lattice of joints is stepped from the origin by at least spacing - spacing_variation; a
    // step below the origin coordinates' round-off would never move (the cutter would not end).
    const double reach = std::max(std::abs(s.origin.x), std::abs(s.origin.y));
    if (reach * 1e-9 > s.spacing - s.spacingVariation)
      j.fail("origin", "lies " + shown(reach) + " m out, too far for joints " + shown(s.spacing - s.spacingVariation) +
                           " m apart to be stepped from it: give an origin within 1e9 spacings of the region");
    region.jointSets.push_back(s);
    j.finish();
  }
  return d;
}

}  // namespace

ExcavationDefinition readExcavation(TableReader& r) {
  ExcavationDefinition d;
  d.origin = r.origin();
  ExcavationRegion& region = d.region;
  region.where = r.location();
  if (r.has("circle") == r.has("polygon")) r.failTable("give either circle = { centre, radius } or polygon = [...]");
  if (r.has("circle")) {
    auto c = r.subtable("circle");
    if (!c) r.fail("circle", "must be a table { centre = [x, y], radius = R }");
    region.centre = c->vec2("centre");
    region.radius = c->positive("radius");
    c->finish();
  } else {
    region.polygon = r.polygon("polygon");
    validateBlockPolygon(region.polygon, 0.0, r.location());
  }
  return d;
}

void readBlocks(TableReader& top, SceneDefinition& scene) {
  for (auto [table, prefix] : top.tables("block")) {
    TableReader r(*table, prefix, top.file());
    scene.blocks.push_back(readBlock(r));
    r.finish();
  }
  for (auto [table, prefix] : top.tables("region")) {
    TableReader r(*table, prefix, top.file());
    scene.regions.push_back(readRegion(r));
    r.finish();
  }
  for (auto [table, prefix] : top.tables("excavation")) {
    TableReader r(*table, prefix, top.file());
    scene.excavations.push_back(readExcavation(r));
    r.finish();
  }
}

}  // namespace vdec
