// [fluid], [[flow_boundary]] and the fluid keys of a [[joint_material]] (1.4.2).
#include <cmath>

#include "io/scene_sections.hpp"

namespace vdec {

namespace {

// Hydraulic apertures are micrometres to millimetres; a metre is no joint's, and a^3 of a larger
// one would overflow the cubic law.
double aperture(TableReader& r, const char* key, bool zeroAllowed) {
  const double a = zeroAllowed ? r.nonNegative(key, 0.0) : r.positive(key);
  if (a > 1.0) r.fail(key, "must be at most 1 m (a hydraulic aperture, m), got " + shown(a));
  return a;
}

}  // namespace

void readJointFlowKeys(TableReader& r, JointMaterial& j) {
  // Checked against the [fluid] table by the builder: without it these keys mean nothing.
  if (r.has("aperture")) j.aperture = aperture(r, "aperture", true);
  if (r.has("residual_aperture")) {
    j.residualAperture = aperture(r, "residual_aperture", false);
    if (r.has("aperture") && j.residualAperture > j.aperture)
      r.fail("residual_aperture", "must not exceed aperture (" + shown(j.aperture) + " m), the aperture at zero normal stress");
  }
  if (r.has("max_aperture")) {
    j.maxAperture = aperture(r, "max_aperture", false);
    const double least = std::max(std::isnan(j.aperture) ? 0.0 : j.aperture,
                                  std::isnan(j.residualAperture) ? 0.0 : j.residualAperture);
    if (j.maxAperture < least)
      r.fail("max_aperture", "must be at least aperture and residual_aperture (" + shown(least) + " m)");
  }
  if (r.has("point_permeability")) {
    if (j.law != JointLaw::PointContact)
      r.fail("point_permeability", "is the flow law of the point-contact joint law (1.4-7); joints of the other laws "
                                   "pass fluid by the cubic law of their aperture (1.4-8)");
    j.pointPermeability = r.nonNegative("point_permeability", 0.0);
  }
}

FlowBoundaryDefinition readFlowBoundary(TableReader& r) {
  FlowBoundaryDefinition d;
  d.origin = r.origin();
  FlowBoundary& b = d.boundary;
  b.name = r.string("name", "");
  const std::vector<double> box = r.numbers("box", 4, "must be [x_min, y_min, x_max, y_max], e.g. [-1.0, 0.0, 0.0, 1.0]");
  b.lo = {box[0], box[1]};
  b.hi = {box[2], box[3]};
  if (!(b.lo.x <= b.hi.x && b.lo.y <= b.hi.y)) r.fail("box", "needs x_min <= x_max and y_min <= y_max");
  const int given = r.has("pressure") + r.has("water_table") + r.has("inflow");
  if (given != 1)
    r.failTable(given == 0 ? "gives no condition: give pressure (Pa), water_table (m) or inflow (m^2/s per unit thickness)"
                           : "give one of pressure, water_table and inflow");
  if (r.has("pressure")) b.value = r.nonNegative("pressure", 0.0);
  if (r.has("water_table")) b.waterTable = r.number("water_table");
  if (r.has("inflow")) {
    b.inflow = true;
    b.value = r.number("inflow");
  }
  if (r.has("history")) d.history = readTimeFunction(r, "history");
  r.finish();
  return d;
}

void readFluid(TableReader& top, SceneDefinition& scene) {
  if (auto t = top.subtable("fluid")) {
    FluidDefinition d;
    d.origin = t->origin();
    FluidProperties& f = d.fluid;
    f.density = t->has("density") ? t->positive("density") : 1000.0;
    f.bulkModulus = t->positive("bulk_modulus");
    f.viscosity = t->positive("viscosity");
    f.yieldStress = t->nonNegative("yield_stress", 0.0);
    const std::string law = t->string("bingham_law", "linear");
    if (law == "buckingham") f.buckingham = true;
    else if (law != "linear") t->fail("bingham_law", "unknown law '" + law + "'; use linear or buckingham");
    if (t->has("bingham_law") && f.yieldStress == 0.0)
      t->fail("bingham_law", "applies to a Bingham fluid: give yield_stress > 0 too");
    const std::string scheme = t->string("scheme", "explicit");
    if (scheme == "implicit") f.scheme = FlowScheme::Implicit;
    else if (scheme == "steady") f.scheme = FlowScheme::Steady;
    else if (scheme != "explicit") t->fail("scheme", "unknown scheme '" + scheme + "'; use explicit, implicit or steady");
    if (f.scheme != FlowScheme::Explicit && t->has("step_fraction"))
      t->fail("step_fraction", "sets the explicit scheme's sub-step; the '" + scheme + "' scheme takes none");
    f.initialPressure = t->nonNegative("initial_pressure", 0.0);
    if (t->has("water_table")) f.waterTable = t->number("water_table");
    if (t->has("initial_saturation")) {
      f.initialSaturation = t->nonNegative("initial_saturation", 1.0);
      if (f.initialSaturation > 1.0)
        t->fail("initial_saturation", "must be in [0, 1]: the fraction of their volume the domains at zero initial "
                                      "pressure hold (1 full, 0 dry)");
      if (f.initialPressure > 0.0)
        t->fail("initial_saturation", "applies to the domains at zero initial pressure, and initial_pressure > 0 "
                                      "leaves none: drop one of the two (with a water_table, the domains above it "
                                      "start at initial_pressure)");
    }
    if (t->has("step_fraction")) {
      f.stepFraction = t->positive("step_fraction");
      if (f.stepFraction > 4.0)
        t->fail("step_fraction", "must be in (0, 4]: the fluid sub-step as a fraction of the limit 1.4-11 (0.8 by "
                                 "default; above 1 the explicit flow may be unstable, which the run detects)");
    }
    if (t->has("min_domain_area")) f.minDomainArea = t->positive("min_domain_area");
    d.flowing = t->boolean("flow", true);
    t->finish();
    scene.fluid = d;
  }
  for (auto [table, prefix] : top.tables("flow_boundary")) {
    TableReader r(*table, prefix, top.file());
    scene.flowBoundaries.push_back(readFlowBoundary(r));
  }
}

}  // namespace vdec
