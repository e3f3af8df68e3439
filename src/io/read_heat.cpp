// [heat], [[heat_boundary]], [[heat_source]] and the thermal keys of a [[block_material]] (1.4.3).
#include <cmath>

#include "io/scene_sections.hpp"

namespace vdec {

namespace {

// decay = [[a1, tau1], [a2, tau2], ...]: the load times sum a_k exp(-t / tau_k).
HeatDecay readDecay(TableReader& r) {
  HeatDecay decay;
  if (!r.has("decay")) return decay;
  const std::vector<double> flat = r.pairs("decay", "must be an array of [fraction, time] pairs, e.g. [[0.6, 3.2e8], [0.4, 3.2e9]]");
  for (std::size_t k = 0; k + 1 < flat.size(); k += 2) {
    if (!(flat[k + 1] > 0.0)) r.fail("decay", "each pair's time constant (s) must be > 0, got " + shown(flat[k + 1]));
    decay.push_back({flat[k], flat[k + 1]});
  }
  if (decay.empty()) r.fail("decay", "must hold at least one [fraction, time] pair");
  return decay;
}

HeatBoundaryDefinition readHeatBoundary(TableReader& r) {
  HeatBoundaryDefinition d;
  d.origin = r.origin();
  const int given = r.has("temperature") + r.has("flux") + r.has("convection") + r.has("radiation");
  if (given != 1)
    r.failTable(given == 0 ? "sets nothing: give temperature, flux (W/m^2 into the body), convection = { h, ambient } or "
                             "radiation = { emissivity, ambient }"
                           : "give one of temperature, flux, convection and radiation");
  if (r.has("temperature")) {
    d.kind = HeatBoundaryDefinition::Kind::Temperature;
    d.value = r.number("temperature");
  } else if (r.has("flux")) {
    d.kind = HeatBoundaryDefinition::Kind::Flux;
    d.value = r.number("flux");
  } else if (r.has("radiation")) {
    d.kind = HeatBoundaryDefinition::Kind::Radiation;
    auto c = r.subtable("radiation");
    if (!c) r.fail("radiation", "must be a table, written radiation = { emissivity = 0.9, ambient = 293.15 }");
    d.value = c->positive("emissivity");
    if (d.value > 1.0) c->fail("emissivity", "must be in (0, 1], got " + shown(d.value));
    d.ambient = c->positive("ambient");
    c->finish();
  } else {
    d.kind = HeatBoundaryDefinition::Kind::Convection;
    auto c = r.subtable("convection");
    if (!c) r.fail("convection", "must be a table, written convection = { h = 10.0, ambient = 20.0 }");
    d.value = c->positive("h");
    d.ambient = c->number("ambient");
    c->finish();
  }
  if (r.has("decay")) {
    if (d.kind != HeatBoundaryDefinition::Kind::Flux) r.fail("decay", "applies to a flux; a temperature or convection does not decay");
    d.decay = readDecay(r);
  }
  if (r.has("history")) {
    if (d.kind == HeatBoundaryDefinition::Kind::Convection || d.kind == HeatBoundaryDefinition::Kind::Radiation)
      r.fail("history", "applies to a temperature or a flux; a convection's or radiation's ambient temperature is constant");
    d.history = readTimeFunction(r, "history");
  }
  d.block = r.string("block", "");
  readSelection(r, d);
  return d;
}

HeatSourceDefinition readHeatSource(TableReader& r) {
  HeatSourceDefinition d;
  d.origin = r.origin();
  if (r.has("point") == r.has("block"))
    r.failTable("give either point = [x, y] (a line source at a gridpoint, with power in W/m) or block = NAME (a "
                "volumetric source, with power_density in W/m^3)");
  if (r.has("point")) {
    d.point = r.vec2("point");
    d.power = r.number("power");
    if (r.has("power_density")) r.fail("power_density", "is a block's source; a point source takes power (W/m)");
  } else {
    d.atPoint = false;
    d.block = r.string("block");
    d.power = r.number("power_density");
    if (r.has("power")) r.fail("power", "is a point source's; a block's source takes power_density (W/m^3)");
  }
  d.decay = readDecay(r);
  return d;
}

}  // namespace

void readThermalKeys(TableReader& r, BlockMaterial& mat) {
  const bool isotropic = r.has("conductivity");
  const bool directional = r.has("conductivity_x") || r.has("conductivity_y") || r.has("conductivity_angle");
  if (isotropic && directional)
    r.fail("conductivity", "give either conductivity (isotropic) or conductivity_x and conductivity_y (and conductivity_angle)");
  if (isotropic) mat.conductivityX = mat.conductivityY = r.positive("conductivity");
  if (directional) {
    mat.conductivityX = r.positive("conductivity_x");
    mat.conductivityY = r.positive("conductivity_y");
    const double angle = r.number("conductivity_angle", 0.0);
    if (!(angle >= -360.0 && angle <= 360.0)) r.fail("conductivity_angle", "must be in [-360, 360] degrees, got " + shown(angle));
    mat.conductivityAngle = radians(angle);
  }
  if (r.has("specific_heat")) mat.specificHeat = r.positive("specific_heat");
  if (r.has("expansion")) {
    mat.expansion = r.nonNegative("expansion", 0.0);
    if (mat.expansion > 1e-3) r.fail("expansion", "must be at most 1e-3 per degree (a linear expansion coefficient; rock's are near 1e-5), got " + shown(mat.expansion));
    if (!mat.elastic()) r.fail("expansion", "needs the elastic constants (young and poisson, or bulk and shear): the expansion loads the zones through their bulk modulus");
  }
}

void readHeat(TableReader& top, SceneDefinition& scene) {
  if (auto t = top.subtable("heat")) {
    HeatDefinition d;
    d.origin = t->origin();
    d.initialTemperature = t->number("initial_temperature", 0.0);
    d.theta = t->number("theta", 0.0);
    if (!(d.theta >= 0.0 && d.theta <= 1.0)) t->fail("theta", "must be in [0, 1] (0 explicit, 0.5 Crank-Nicolson, 1 backward Euler), got " + shown(d.theta));
    if (t->has("step")) d.step = t->positive("step");
    else if (d.theta > 0.0) t->fail("step", "is required with theta > 0: the implicit scheme is stable at any step, so choose it for accuracy (s)");
    d.time = t->nonNegative("time", 0.0);
    t->finish();
    scene.heat = d;
  }
  for (auto [table, prefix] : top.tables("heat_boundary")) {
    TableReader r(*table, prefix, top.file());
    scene.heatBoundaries.push_back(readHeatBoundary(r));
    r.finish();
  }
  for (auto [table, prefix] : top.tables("heat_source")) {
    TableReader r(*table, prefix, top.file());
    scene.heatSources.push_back(readHeatSource(r));
    r.finish();
  }
}

}  // namespace vdec
