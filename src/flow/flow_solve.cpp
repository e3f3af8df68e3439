#include "flow/flow_solve.hpp"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "core/errors.hpp"
#include "core/shown.hpp"
#include "flow/flow_network.hpp"
#include "flow/fracture_flow.hpp"

namespace vdec {

namespace {

// Newton iterations of a Bingham fluid's solve before it is called unsettled.
constexpr int kMostNewtonIterations = 100;
// A domain's net outflow, over the scale of its rounding (the sum over its knots of C times the
// pressures and threshold its flow is formed from), below which it balances: some 5000 eps.
constexpr double kBalanced = 1e-12;
// The share of its conductance a knot below its threshold keeps in the Newton matrix, so that the
// matrix stays positive definite over domains no flowing knot reaches; it does not enter the flows.
constexpr double kDeadKnotStiffness = 1e-6;
// Bisections of the line search along a Newton step.
constexpr int kLineSearchHalvings = 40;

// A linear system over the unknown domains, solved by LDLT.
Eigen::VectorXd solveSystem(const Model& m, int count, const std::vector<Eigen::Triplet<double>>& entries,
                            const Eigen::VectorXd& rhs, bool steady) {
  Eigen::SparseMatrix<double> a(count, count);
  a.setFromTriplets(entries.begin(), entries.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(a);
  Eigen::VectorXd solved;
  if (solver.info() == Eigen::Success) solved = solver.solve(rhs);
  if (solver.info() != Eigen::Success || !solved.allFinite()) {
    std::ostringstream s;
    s << "the " << (steady ? "steady" : "implicit") << " flow solve over " << count << " domains failed at cycle "
      << m.cycle << ": the network's conductances or areas are not of a size a double can take; check the joints' "
      << "apertures and [fluid] viscosity and bulk_modulus";
    throw InstabilityError(s.str());
  }
  return solved;
}

}  // namespace

void solveFlow(Model& m, const std::vector<double>& conductance, double h, bool steady) {
  FlowState& fs = m.flow;
  const int n = static_cast<int>(fs.domains.size());
  const double kw = fs.fluid.bulkModulus;
  // Piezometric pressure p* = p + offset, offset = -rho_w g . x.
  auto offset = [&](Vec2 at) { return -fs.fluid.density * dot(m.gravity, at); };
  auto heldMouth = [&](const FlowKnot& k) { return k.boundary >= 0; };

  // Steady: only the domains from which fluid can reach a held pressure have a steady pressure;
  // the others keep theirs (no flow reaches or leaves them).
  // The domains each domain passes fluid to directly.
  std::vector<std::vector<int>> links(n);
  for (std::size_t k = 0; k < fs.knots.size(); ++k) {
    const FlowKnot& knot = fs.knots[k];
    if (knot.domain[0] >= 0 && knot.domain[1] >= 0 && conductance[k] > 0.0) {
      links[knot.domain[0]].push_back(knot.domain[1]);
      links[knot.domain[1]].push_back(knot.domain[0]);
    }
  }
  std::vector<char> reached(n, steady ? 0 : 1);
  if (steady) {
    std::vector<int> stack;
    for (int d = 0; d < n; ++d)
      if (fs.domains[d].fixed) reached[d] = 1, stack.push_back(d);
    for (const FlowKnot& k : fs.knots)
      if (heldMouth(k) && conductance[&k - fs.knots.data()] > 0.0)
        for (const int d : k.domain)
          if (d >= 0 && !reached[d]) reached[d] = 1, stack.push_back(d);
    while (!stack.empty()) {
      const int d = stack.back();
      stack.pop_back();
      for (const int e : links[d])
        if (!reached[e]) reached[e] = 1, stack.push_back(e);
    }
  }
  std::vector<double> source(n, 0.0);
  std::vector<int> fed(fs.boundaries.size(), 0);
  for (const FlowDomain& d : fs.domains)
    if (d.boundary >= 0 && !d.fixed && fs.boundaries[d.boundary].inflow) ++fed[d.boundary];
  for (int d = 0; d < n; ++d) {
    const FlowDomain& dom = fs.domains[d];
    if (dom.boundary < 0 || dom.fixed || !fs.boundaries[dom.boundary].inflow) continue;
    source[d] = boundaryValue(m, fs.boundaries[dom.boundary], dom.centre) / fed[dom.boundary];
    if (steady && !reached[d]) {
      std::ostringstream s;
      s << "steady flow has no solution: fluid flows into the domain at (" << shown(dom.centre.x) << ", "
        << shown(dom.centre.y) << ") and cannot leave, no held pressure being reachable from it; hold a pressure "
        << "where it can leave ([[flow_boundary]] pressure), or use [fluid] scheme = \"implicit\" or \"explicit\"";
      throw InstabilityError(s.str());
    }
  }

  std::vector<int> unknown(n, -1);
  int count = 0;
  for (int d = 0; d < n; ++d)
    // A partly saturated domain stays at zero pressure while it fills (implicit): known, not solved for.
    if (!fs.domains[d].fixed && reached[d] && (steady || fs.domains[d].content >= fs.domains[d].area)) unknown[d] = count++;
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(count);
  for (int d = 0; d < n; ++d) {
    if (unknown[d] < 0) continue;
    const FlowDomain& dom = fs.domains[d];
    rhs[unknown[d]] += source[d];
    if (!steady) {
      const double storage = dom.area / (kw * h);
      entries.emplace_back(unknown[d], unknown[d], storage);
      rhs[unknown[d]] += storage * (dom.pressure + offset(dom.centre));
    }
  }
  // Each side of a knot: an unknown, a known piezometric pressure, or shut (an impermeable mouth).
  auto sideOf = [&](const FlowKnot& k, int i, int& u, double& known) {
    const int d = k.domain[i];
    if (d >= 0) {
      u = unknown[d];
      known = fs.domains[d].pressure + offset(fs.domains[d].centre);
      return true;
    }
    u = -1;
    if (!heldMouth(k)) return false;
    known = boundaryValue(m, fs.boundaries[k.boundary], k.point) + offset(k.point);
    return true;
  };
  for (std::size_t k = 0; k < fs.knots.size(); ++k) {
    const double c = conductance[k];
    int u[2];
    double known[2];
    if (!sideOf(fs.knots[k], 0, u[0], known[0]) || !sideOf(fs.knots[k], 1, u[1], known[1]) || c == 0.0) continue;
    for (int i = 0; i < 2; ++i) {
      if (u[i] < 0) continue;
      entries.emplace_back(u[i], u[i], c);
      if (u[1 - i] >= 0) entries.emplace_back(u[i], u[1 - i], -c);
      else rhs[u[i]] += c * known[1 - i];
    }
  }
  Eigen::VectorXd solved;
  if (count > 0) solved = solveSystem(m, count, entries, rhs, steady);
  // The flow through every knot from the solved pressures moves the fluid, as a sub-step does.
  std::vector<double> piezometric(n);
  for (int d = 0; d < n; ++d)
    piezometric[d] = unknown[d] >= 0 ? solved[unknown[d]] : fs.domains[d].pressure + offset(fs.domains[d].centre);
  fs.solveIterations = 1;
  if (fs.fluid.yieldStress > 0.0 && count > 0) {
    // A Bingham fluid: the Newtonian pressures above start Newton's method on the balance of the
    // unknown domains, the gradient of a convex potential (the knots' laws are monotone), damped
    // by a line search along each step: plain Newton cycles between sets of flowing knots.
    auto pressureOf = [&](const std::vector<double>& p, const FlowKnot& k, int i) {
      const int d = k.domain[i];
      return d >= 0 ? p[d] : boundaryValue(m, fs.boundaries[k.boundary], k.point) + offset(k.point);
    };
    auto open = [&](std::size_t k) {
      const FlowKnot& knot = fs.knots[k];
      return (knot.domain[0] >= 0 || heldMouth(knot)) && (knot.domain[1] >= 0 || heldMouth(knot)) && conductance[k] > 0.0;
    };
    // Each unknown domain's net outflow less its source, plus its storage's rate (implicit), and
    // the sum of the sizes of those terms (the scale of its rounding).
    Eigen::VectorXd size(count);
    auto imbalance = [&](const std::vector<double>& p) {
      Eigen::VectorXd g = Eigen::VectorXd::Zero(count);
      size.setZero();
      auto add = [&](int d, double term, double rounding) {
        g[unknown[d]] += term;
        size[unknown[d]] += rounding;
      };
      for (int d = 0; d < n; ++d) {
        if (unknown[d] < 0) continue;
        add(d, -source[d], std::abs(source[d]));
        if (steady) continue;
        const double storage = fs.domains[d].area / (kw * h), before = fs.domains[d].pressure + offset(fs.domains[d].centre);
        add(d, storage * (p[d] - before), storage * (std::abs(p[d]) + std::abs(before)));
      }
      for (std::size_t k = 0; k < fs.knots.size(); ++k) {
        if (!open(k)) continue;
        const FlowKnot& knot = fs.knots[k];
        const double p0 = pressureOf(p, knot, 0), p1 = pressureOf(p, knot, 1);
        const double q = knotFlow(m, knot, conductance[k], p0 - p1);
        // Its rounding scales with the pressures it is the difference of, and the threshold.
        const double rounding = conductance[k] * (std::abs(p0) + std::abs(p1) + 2.0 * fs.fluid.yieldStress * knot.length / knot.aperture);
        if (knot.domain[0] >= 0 && unknown[knot.domain[0]] >= 0) add(knot.domain[0], q, rounding);
        if (knot.domain[1] >= 0 && unknown[knot.domain[1]] >= 0) add(knot.domain[1], -q, rounding);
      }
      return g;
    };
    auto balances = [&](const Eigen::VectorXd& g) {
      for (int i = 0; i < count; ++i)
        if (std::abs(g[i]) > kBalanced * size[i]) return false;
      return true;
    };
    auto moved = [&](double alpha, const Eigen::VectorXd& step) {
      std::vector<double> p = piezometric;
      for (int d = 0; d < n; ++d)
        if (unknown[d] >= 0) p[d] += alpha * step[unknown[d]];
      return p;
    };
    for (Eigen::VectorXd g = imbalance(piezometric); !balances(g); g = imbalance(piezometric)) {
      if (fs.solveIterations > kMostNewtonIterations) {
        std::ostringstream s;
        s << "the " << (steady ? "steady" : "implicit") << " flow of the Bingham fluid did not settle at cycle " << m.cycle
          << ": after " << kMostNewtonIterations << " Newton iterations a domain still gains or loses "
          << shown(g.lpNorm<Eigen::Infinity>()) << " m^2/s; use [fluid] scheme = \"explicit\"";
        throw InstabilityError(s.str());
      }
      ++fs.solveIterations;
      // The tangent of the knots' laws: C (1 - r^3) for Buckingham's, C for the linear law's,
      // on the flowing knots; a little of C on those below the threshold.
      std::vector<Eigen::Triplet<double>> tangent;
      for (int d = 0; d < n; ++d)
        if (unknown[d] >= 0 && !steady) tangent.emplace_back(unknown[d], unknown[d], fs.domains[d].area / (kw * h));
      for (std::size_t k = 0; k < fs.knots.size(); ++k) {
        if (!open(k)) continue;
        const FlowKnot& knot = fs.knots[k];
        const double dp = pressureOf(piezometric, knot, 0) - pressureOf(piezometric, knot, 1);
        const double c = conductance[k];
        double slope = kDeadKnotStiffness * c;
        if (knotFlow(m, knot, c, dp) != 0.0) {
          const double r = 2.0 * fs.fluid.yieldStress * knot.length / (knot.aperture * std::abs(dp));
          slope = std::max(slope, fs.fluid.buckingham ? c * (1.0 - r * r * r) : c);
        }
        int u[2];
        for (int i = 0; i < 2; ++i) u[i] = knot.domain[i] >= 0 ? unknown[knot.domain[i]] : -1;
        for (int i = 0; i < 2; ++i) {
          if (u[i] < 0) continue;
          tangent.emplace_back(u[i], u[i], slope);
          if (u[1 - i] >= 0) tangent.emplace_back(u[i], u[1 - i], -slope);
        }
      }
      const Eigen::VectorXd step = solveSystem(m, count, tangent, -g, steady);
      // The potential's slope along the step rises with alpha (it is convex): its zero in (0, 1], or 1.
      auto slopeAt = [&](double alpha) { return imbalance(moved(alpha, step)).dot(step); };
      double alpha = 1.0;
      if (slopeAt(1.0) > 0.0) {
        double lo = 0.0, hi = 1.0;
        for (int i = 0; i < kLineSearchHalvings; ++i) {
          const double mid = 0.5 * (lo + hi);
          (slopeAt(mid) > 0.0 ? hi : lo) = mid;
        }
        alpha = 0.5 * (lo + hi);
      }
      piezometric = moved(alpha, step);
    }
  }
  // Steady: a group of domains that no held pressure reaches comes to rest at one piezometric
  // pressure, the one at which it holds the fluid it has (hydrostatic under gravity).
  std::vector<char> settled(n, 0);
  std::vector<double> restContent(n, -1.0);  // of a group's domains not all full; -1 elsewhere
  if (steady) {
    for (int start = 0; start < n; ++start) {
      if (reached[start] || settled[start] || fs.domains[start].fixed) continue;
      std::vector<int> group{start};
      settled[start] = 1;
      for (std::size_t i = 0; i < group.size(); ++i)
        for (const int e : links[group[i]])
          if (!settled[e]) settled[e] = 1, group.push_back(e);
      // The fluid fills the group from its lowest domain up: below the level full, under the
      // hydrostatic pressure from it; the domain at the level partly saturated; those above dry.
      std::sort(group.begin(), group.end(), [&](int a, int b) {
        const double oa = offset(fs.domains[a].centre), ob = offset(fs.domains[b].centre);
        return oa != ob ? oa < ob : a < b;
      });
      double content = 0.0;
      for (const int d : group) content += fs.domains[d].content;
      double area = 0.0, weighted = 0.0;
      std::size_t full = 0;
      for (; full < group.size(); ++full) {
        const FlowDomain& next = fs.domains[group[full]];
        const double level = offset(next.centre);
        // What the domains below hold with the level at this domain's centre, and this one full too.
        const double below = area + (area * level - weighted) / kw;
        if (content < below + next.area) break;
        area += next.area;
        weighted += next.area * level;
      }
      if (full == group.size()) {
        const double level = (kw * (content - area) + weighted) / area;
        for (const int d : group) piezometric[d] = level;
      } else {
        const int partial = group[full];
        const double level = offset(fs.domains[partial].centre);
        const double below = area + (area * level - weighted) / kw;
        for (std::size_t i = 0; i < group.size(); ++i) {
          const int d = group[i];
          piezometric[d] = i < full ? level : offset(fs.domains[d].centre);
          restContent[d] = i < full ? fs.domains[d].area * (1.0 + (level - offset(fs.domains[d].centre)) / kw)
                           : i == full ? std::max(content - below, 0.0) : 0.0;
        }
      }
    }
  }
  for (std::size_t k = 0; k < fs.knots.size(); ++k) {
    FlowKnot& knot = fs.knots[k];
    int u[2];
    double known[2];
    if (!sideOf(knot, 0, u[0], known[0]) || !sideOf(knot, 1, u[1], known[1])) {
      knot.flow = 0.0;
      continue;
    }
    const double p0 = knot.domain[0] >= 0 ? piezometric[knot.domain[0]] : known[0];
    const double p1 = knot.domain[1] >= 0 ? piezometric[knot.domain[1]] : known[1];
    // A group at rest passes nothing (its dry domains' heads differ, and no fluid is there to pass).
    const bool atRest = knot.domain[0] >= 0 && knot.domain[1] >= 0 && settled[knot.domain[0]] && settled[knot.domain[1]];
    knot.flow = atRest ? 0.0 : knotFlow(m, knot, conductance[k], p0 - p1);
  }
  if (!steady) limitDrainage(fs, h);
  for (const FlowKnot& knot : fs.knots) passThroughKnot(fs, knot, knot.flow * h);
  for (int d = 0; d < n; ++d) {
    FlowDomain& dom = fs.domains[d];
    if (source[d] != 0.0) {
      dom.content += source[d] * h;
      fs.totals.inflow += source[d] * h;
    }
    if (dom.fixed) {
      const double held = boundaryValue(m, fs.boundaries[dom.boundary], dom.centre);
      const double content = dom.area * (1.0 + held / kw);
      if (content > dom.content) fs.totals.inflow += content - dom.content;
      else fs.totals.outflow += dom.content - content;
      dom.content = content;
      dom.pressure = held;
    } else if (steady && (unknown[d] >= 0 || settled[d])) {
      // No storage in a steady flow: the domain holds what its steady pressure compresses into
      // it, the difference from what the flow left there given or taken by the solve.
      // A suction in the solve leaves the domain partly saturated at zero pressure.
      const double solvedPressure = piezometric[d] - offset(dom.centre);
      dom.pressure = std::max(solvedPressure, 0.0);
      const double content = restContent[d] >= 0.0 ? restContent[d] : dom.area * (1.0 + solvedPressure / kw);
      if (content > dom.content) fs.totals.created += content - dom.content;
      else fs.totals.removed += dom.content - content;
      dom.content = content;
    } else {
      if (dom.content < 0.0) emptied(fs, dom);
      dom.pressure = domainPressure(kw, dom.content, dom.area);
    }
  }
  fs.subStep = h;
  fs.subSteps = 1;
  ++fs.totals.subSteps;
}

}  // namespace vdec
