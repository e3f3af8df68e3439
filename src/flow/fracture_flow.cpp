#include "flow/fracture_flow.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/errors.hpp"
#include "core/shown.hpp"
#include "flow/flow_network.hpp"
#include "flow/flow_solve.hpp"

namespace vdec {

namespace {

// More fluid sub-steps than this in one mechanical step is a scene to change, not to wait for.
constexpr long long kMostSubSteps = 100000;
// Sub-steps in a row over which a domain's pressure change may alternate in sign without
// decaying before the flow is called unstable: below the stability limit the explicit update
// damps every alternating mode at once (by 1 - 2 step_fraction at worst). Without decay, not
// only with growth: beyond the limit, the zero-pressure floor of partly saturated domains turns
// the growth into a steady alternation (full and drained domains taking turns), as wrong.
constexpr int kSwingLimit = 20;
constexpr double kUndamped = 0.999;
constexpr double kRoundOff = 1e-12;

// p - rho_w g . x: with gravity the fluid flows down its gradient, not the pressure's.
double piezometric(const Model& m, double p, Vec2 at) { return p - m.flow.fluid.density * dot(m.gravity, at); }

void hold(FlowState& fs, FlowDomain& d, double p) {
  const double content = d.area * (1.0 + p / fs.fluid.bulkModulus);
  const double supplied = content - d.content;
  if (supplied > 0.0) fs.totals.inflow += supplied;
  else fs.totals.outflow -= supplied;
  d.content = content;
  d.pressure = p;
}

void holdFixedDomains(Model& m) {
  FlowState& fs = m.flow;
  for (FlowDomain& d : fs.domains)
    if (d.fixed) hold(fs, d, boundaryValue(m, fs.boundaries[d.boundary], d.centre));
}

[[noreturn]] void unstable(const Model& m, const FlowDomain& d, const std::string& what) {
  std::ostringstream s;
  s << "fluid flow unstable at cycle " << m.cycle << ": the pressure of the domain at (" << shown(d.centre.x) << ", "
    << shown(d.centre.y) << ") " << what << " (fluid sub-step " << shown(m.flow.subStep) << " s, " << m.flow.subSteps
    << " per mechanical step); lower [fluid] step_fraction (now " << shown(m.flow.fluid.stepFraction)
    << ", at most 1 is within the stability limit 1.4-11)";
  throw InstabilityError(s.str());
}

}  // namespace

void passThroughKnot(FlowState& fs, const FlowKnot& k, double volume) {
  // A side that is the outside of the model is a held mouth: what passes it enters or leaves.
  if (k.domain[0] >= 0) fs.domains[k.domain[0]].content -= volume;
  else if (volume > 0.0) fs.totals.inflow += volume;
  else fs.totals.outflow -= volume;
  if (k.domain[1] >= 0) fs.domains[k.domain[1]].content += volume;
  else if (volume > 0.0) fs.totals.outflow += volume;
  else fs.totals.inflow -= volume;
}

void emptied(FlowState& fs, FlowDomain& d) {
  // Drained by limitDrainage to what it held, less the round-off of summing its outflows.
  fs.totals.created -= d.content;
  d.content = 0.0;
}

void limitDrainage(FlowState& fs, double h) {
  // A partly saturated domain is at zero pressure, so it drains only under gravity; it passes
  // on at most what it holds, its outflows scaled alike, so that no content goes negative.
  // Called every sub-step while a domain is partly saturated: one buffer kept between calls, holding
  // each domain's outflow and then the factor on it.
  static thread_local std::vector<double> scale;
  scale.assign(fs.domains.size(), 0.0);
  for (const FlowKnot& k : fs.knots) {
    if (k.flow > 0.0 && k.domain[0] >= 0) scale[k.domain[0]] += k.flow * h;
    if (k.flow < 0.0 && k.domain[1] >= 0) scale[k.domain[1]] -= k.flow * h;
  }
  for (std::size_t d = 0; d < fs.domains.size(); ++d) {
    const FlowDomain& dom = fs.domains[d];
    const double out = scale[d];
    scale[d] = !dom.fixed && dom.content < dom.area && out > dom.content ? std::max(dom.content, 0.0) / out : 1.0;
  }
  for (FlowKnot& k : fs.knots) {
    const int from = k.flow > 0.0 ? k.domain[0] : k.domain[1];
    if (from >= 0) k.flow *= scale[from];
  }
}

double knotConductance(const Model& m, const FlowKnot& k) {
  const JointMaterial& j = m.jointMaterials[k.joint];
  if (j.law == JointLaw::PointContact) return j.pointPermeability;  // 1.4-7
  return k.aperture * k.aperture * k.aperture / (12.0 * m.flow.fluid.viscosity * k.length);  // 1.4-8
}

double knotFlow(const Model& m, const FlowKnot& k, double c, double dp) {
  const double tauY = m.flow.fluid.yieldStress;
  if (tauY <= 0.0 || m.jointMaterials[k.joint].law == JointLaw::PointContact) return c * dp;
  // Bingham: no flow below the threshold gradient J0 = 2 tau_y / a (1.4-6), a pressure
  // difference of J0 l across the knot.
  const double threshold = 2.0 * tauY * k.length / k.aperture, size = std::abs(dp);
  if (size <= threshold) return 0.0;
  const double sign = dp > 0.0 ? 1.0 : -1.0;
  if (!m.flow.fluid.buckingham) return sign * c * (size - threshold);
  const double r = threshold / size;
  return c * dp * (1.0 - 1.5 * r + 0.5 * r * r * r);
}

double fluidTimeStep(const Model& m, const std::vector<double>& conductance) {
  const FlowState& fs = m.flow;
  std::vector<double> sum(fs.domains.size(), 0.0);
  for (std::size_t k = 0; k < fs.knots.size(); ++k)
    for (const int d : fs.knots[k].domain)
      if (d >= 0) sum[d] += conductance[k];
  double dt = INFINITY;
  for (std::size_t d = 0; d < fs.domains.size(); ++d)
    if (!fs.domains[d].fixed && sum[d] > 0.0) dt = std::min(dt, fs.domains[d].area / (fs.fluid.bulkModulus * sum[d]));
  return dt;  // 1.4-11
}

void startFlow(Model& m) {
  FlowState& fs = m.flow;
  fs.totals = {};
  fs.domains.clear();
  buildFlowNetwork(m, false);
  holdFixedDomains(m);
  fs.totals.inflow = fs.totals.outflow = 0.0;
  fs.totals.initialContent = flowContent(m);
  Blocks& bl = m.blocks;
  bl.boundaryForce.resize(bl.size());
  bl.boundaryMoment.resize(bl.size());
}

void applyDomainPressures(Model& m) {
  const FlowState& fs = m.flow;
  const Vertices& vx = m.vertices;
  Blocks& bl = m.blocks;
  Gridpoints& g = m.gridpoints;
  for (int s = 0; s < static_cast<int>(fs.sides.size()); ++s) {
    const FlowSide& side = fs.sides[s];
    if (side.domain < 0) continue;
    const double p = fs.domains[side.domain].pressure;
    if (p == 0.0) continue;
    const int b = side.block;
    walkSide(vx, fs.sides, s, [&](int e, double t0, double t1) {
      const VertexGeometry& geo = vx.geometry[e];
      const Vec2 p0 = geo.position + (t0 * geo.edgeLength) * geo.edgeDirection;
      const Vec2 p1 = geo.position + (t1 * geo.edgeLength) * geo.edgeDirection;
      const Vec2 d = p1 - p0;
      const Vec2 force = p * Vec2{-d.y, d.x};  // inwards, normal to the edge, p times its length
      if (!bl.deformable[b]) {
        bl.boundaryForce[b] += force;
        bl.boundaryMoment[b] += cross(0.5 * (p0 + p1) - bl.centroid[b], force);
      } else {
        const double along = 0.5 * (t0 + t1);
        g.tractionForce[vx.gridpoint[e]] += (1.0 - along) * force;
        g.tractionForce[vx.gridpoint[vx.next[e]]] += along * force;
      }
    });
  }
}

namespace {

// How far from steady the flow is: the domains' net inflow over the flow the knots would pass
// under the largest pressure in the model (a dead-end network at rest passes none at all).
// Besides, for the schemes that set the pressures by a solve (steady has no net inflow at all),
// the largest change of a domain's pressure in the step over the pressure scale.
void measureUnbalance(Model& m, const std::vector<double>& conductance, const std::vector<double>& before) {
  FlowState& fs = m.flow;
  std::vector<int> fed(fs.boundaries.size(), 0);
  for (const FlowDomain& d : fs.domains)
    if (d.boundary >= 0 && !d.fixed) ++fed[d.boundary];
  std::vector<double> net(fs.domains.size(), 0.0);
  double scale = 0.0;
  for (const FlowDomain& d : fs.domains) scale = std::max(scale, std::abs(d.pressure));
  double through = 0.0;
  for (std::size_t i = 0; i < fs.knots.size(); ++i) {
    const FlowKnot& k = fs.knots[i];
    if (k.domain[0] >= 0) net[k.domain[0]] -= k.flow;
    if (k.domain[1] >= 0) net[k.domain[1]] += k.flow;
    through += conductance[i];
    if (k.boundary >= 0) scale = std::max(scale, std::abs(boundaryValue(m, fs.boundaries[k.boundary], k.point)));
  }
  through *= std::max(scale, 1.0);
  double unbalanced = 0.0;
  for (std::size_t d = 0; d < fs.domains.size(); ++d) {
    const FlowDomain& dom = fs.domains[d];
    if (dom.fixed) continue;
    // A source's inflow counts against the knots'.
    if (dom.boundary >= 0 && fs.boundaries[dom.boundary].inflow)
      net[d] += boundaryValue(m, fs.boundaries[dom.boundary], dom.centre) / fed[dom.boundary];
    unbalanced += std::abs(net[d]);
  }
  fs.unbalancedRatio = through > 0.0 ? unbalanced / through : 0.0;
  if (fs.fluid.scheme != FlowScheme::Explicit) {
    double change = before.size() == fs.domains.size() ? 0.0 : 1.0;
    for (std::size_t d = 0; d < before.size() && d < fs.domains.size(); ++d)
      change = std::max(change, std::abs(fs.domains[d].pressure - before[d]) / std::max(scale, 1.0));
    fs.unbalancedRatio = std::max(fs.unbalancedRatio, change);
  }
}

}  // namespace

void stepFlow(Model& m, double dt) {
  FlowState& fs = m.flow;
  std::vector<double> before;
  for (const FlowDomain& d : fs.domains) before.push_back(d.pressure);
  buildFlowNetwork(m, true);
  holdFixedDomains(m);
  // The apertures are those the motion left: the conductances hold over the step.
  std::vector<double> conductance(fs.knots.size());
  for (std::size_t k = 0; k < fs.knots.size(); ++k) conductance[k] = knotConductance(m, fs.knots[k]);
  if (fs.fluid.scheme != FlowScheme::Explicit) {
    solveFlow(m, conductance, dt, fs.fluid.scheme == FlowScheme::Steady);
    measureUnbalance(m, conductance, before);
    return;
  }
  const double kw = fs.fluid.bulkModulus;
  const double dtFluid = fluidTimeStep(m, conductance);
  const double subSteps = std::isfinite(dtFluid) ? std::ceil(dt / (fs.fluid.stepFraction * dtFluid)) : 1.0;
  if (subSteps > kMostSubSteps) {
    std::ostringstream s;
    s << "the fluid's stable step (1.4-11) is " << shown(dtFluid) << " s, " << shown(subSteps)
      << " fluid sub-steps in one mechanical step of " << shown(dt) << " s (at most " << kMostSubSteps
      << "): lower [fluid] bulk_modulus, raise min_domain_area, or lower the joints' max_aperture";
    throw InstabilityError(s.str());
  }
  const int n = std::max(1, static_cast<int>(subSteps));
  const double h = dt / n;
  fs.subStep = h;
  fs.subSteps = n;
  // Sources: each inflow boundary's rate shared by the domains it feeds.
  std::vector<int> fed(fs.boundaries.size(), 0);
  for (const FlowDomain& d : fs.domains)
    if (d.boundary >= 0 && !d.fixed) ++fed[d.boundary];
  std::vector<double> rate(fs.boundaries.size(), 0.0);
  for (std::size_t b = 0; b < fs.boundaries.size(); ++b)
    if (fs.boundaries[b].inflow && fed[b] > 0) rate[b] = boundaryValue(m, fs.boundaries[b], {}) / fed[b];
  bool partlySaturated = false;
  for (const FlowDomain& d : fs.domains) partlySaturated = partlySaturated || (!d.fixed && d.content < d.area);
  for (int step = 0; step < n; ++step) {
    for (std::size_t kk = 0; kk < fs.knots.size(); ++kk) {
      FlowKnot& k = fs.knots[kk];
      double side[2];
      bool open = true;
      for (int i = 0; i < 2; ++i) {
        const int d = k.domain[i];
        if (d >= 0) side[i] = piezometric(m, fs.domains[d].pressure, fs.domains[d].centre);
        else if (k.boundary >= 0) side[i] = piezometric(m, boundaryValue(m, fs.boundaries[k.boundary], k.point), k.point);
        else open = false;  // a mouth no boundary holds: impermeable
      }
      if (!open) {
        k.flow = 0.0;
        continue;
      }
      k.flow = knotFlow(m, k, conductance[kk], side[0] - side[1]);
    }
    if (partlySaturated) limitDrainage(fs, h);
    for (const FlowKnot& k : fs.knots) passThroughKnot(fs, k, k.flow * h);
    partlySaturated = false;
    for (FlowDomain& d : fs.domains) {
      if (d.fixed) {
        hold(fs, d, boundaryValue(m, fs.boundaries[d.boundary], d.centre));
        continue;
      }
      if (d.boundary >= 0) {
        d.content += rate[d.boundary] * h;
        fs.totals.inflow += rate[d.boundary] * h;
      }
      if (d.content < 0.0) emptied(fs, d);
      const double p = domainPressure(kw, d.content, d.area);
      if (!std::isfinite(p)) unstable(m, d, "is no longer a finite number");
      partlySaturated = partlySaturated || d.content < d.area;
      const double change = p - d.pressure;
      // Round-off swings too, at steady flow: a swing counts above its level (a content's last
      // digits times K_w).
      const bool swings = change * d.lastChange < 0.0 && std::abs(change) >= kUndamped * std::abs(d.lastChange) &&
                          std::abs(change) > kRoundOff * (kw + std::abs(p));
      d.swings = swings ? d.swings + 1 : 0;
      if (d.swings >= kSwingLimit)
        unstable(m, d, "has swung back and forth without decaying for " + std::to_string(kSwingLimit) + " sub-steps");
      d.lastChange = change;
      d.pressure = p;
    }
  }
  fs.totals.subSteps += n;
  measureUnbalance(m, conductance, before);
}

double fluidMechanicalTimeStep(const Model& m, double frac) {
  const FlowState& fs = m.flow;
  const Vertices& vx = m.vertices;
  const Blocks& bl = m.blocks;
  const Gridpoints& g = m.gridpoints;
  std::vector<double> blockK(bl.size(), 0.0), pointK(g.size(), 0.0);
  // A domain's fluid is a spring K_w dA / A on the motion of the blocks around it; its stiffness
  // on one of them is at most K_w (its share of the perimeter) (the perimeter) / area (Gershgorin
  // on K_w g g^T / A, g the perimeter shares), and largest at the residual apertures.
  std::vector<double> stiffest(fs.domains.size(), 0.0);
  for (int s = 0; s < static_cast<int>(fs.sides.size()); ++s) {
    const FlowSide& side = fs.sides[s];
    if (side.domain < 0) continue;
    const FlowKnot& k0 = fs.knots[side.knot];
    const FlowKnot& k1 = fs.knots[fs.sides[side.next].knot];
    const double residuals = m.jointMaterials[k0.joint].residualAperture + m.jointMaterials[k1.joint].residualAperture;
    double length = 0.0;
    walkSide(vx, fs.sides, s, [&](int e, double t0, double t1) { length += (t1 - t0) * vx.geometry[e].edgeLength; });
    stiffest[side.domain] += 0.25 * length * residuals;  // the least area: hydraulic, at residual apertures
  }
  for (std::size_t d = 0; d < fs.domains.size(); ++d) {
    const FlowDomain& dom = fs.domains[d];
    stiffest[d] = dom.fixed ? 0.0 : fs.fluid.bulkModulus * dom.perimeter / std::max({stiffest[d], fs.fluid.minDomainArea, 1e-300});
  }
  for (int s = 0; s < static_cast<int>(fs.sides.size()); ++s) {
    const FlowSide& side = fs.sides[s];
    if (side.domain < 0 || stiffest[side.domain] == 0.0) continue;
    const double c = stiffest[side.domain];
    walkSide(vx, fs.sides, s, [&](int e, double t0, double t1) {
      const double l = (t1 - t0) * vx.geometry[e].edgeLength;
      if (!bl.deformable[side.block]) {
        blockK[side.block] += c * l;
      } else {
        const double along = 0.5 * (t0 + t1);
        pointK[vx.gridpoint[e]] += c * l * (1.0 - along);
        pointK[vx.gridpoint[vx.next[e]]] += c * l * along;
      }
    });
  }
  double dt = INFINITY;
  for (int b = 0; b < bl.size(); ++b)
    if (blockK[b] > 0.0 && bl.movesFreely(b)) dt = std::min(dt, frac * 2.0 * std::sqrt(bl.mass[b] / blockK[b]));
  for (int i = 0; i < g.size(); ++i)
    if (pointK[i] > 0.0 && (g.driven[i] & (DriveX | DriveY)) != (DriveX | DriveY)) dt = std::min(dt, std::sqrt(g.mass[i] / pointK[i]));
  return dt;
}

double flowContent(const Model& m) {
  double sum = 0.0;
  for (const FlowDomain& d : m.flow.domains) sum += d.content;
  return sum;
}

double flowImbalance(const Model& m) {
  const FlowTotals& t = m.flow.totals;
  return t.inflow - t.outflow + t.created - t.removed - (flowContent(m) - t.initialContent);
}

}  // namespace vdec
