#include "structure/beams.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vdec {

namespace {

// An angle brought to (-pi, pi].
double wrapped(double a) {
  constexpr double pi = std::numbers::pi;
  while (a > pi) a -= 2.0 * pi;
  while (a <= -pi) a += 2.0 * pi;
  return a;
}

// The unit direction along the beam at a node: the mean of its elements' chords.
Vec2 nodeTangent(const Model& m, int node) {
  const Structures& st = m.structures;
  const Beam& beam = st.beams[st.nodes.beam[node]];
  const int local = node - beam.firstNode;
  Vec2 sum;
  auto add = [&](int e) {
    if (e < 0) return;
    const Vec2 d = st.nodes.position[st.elements.node[e][1]] - st.nodes.position[st.elements.node[e][0]];
    sum += (1.0 / norm(d)) * d;
  };
  const int before = local > 0 ? beam.firstElement + local - 1 : (beam.closed ? beam.firstElement + beam.elementCount - 1 : -1);
  const int after = local < beam.elementCount ? beam.firstElement + local : -1;
  add(before);
  add(after);
  return (1.0 / norm(sum)) * sum;
}

// Where a tie holds the rock now, its velocity, and the centre of its host (to tell which side of
// the beam the rock is on).
struct HostPoint {
  Vec2 position, velocity, centre, arm;
};

HostPoint hostPoint(const Model& m, const BeamTie& t) {
  HostPoint h;
  if (t.zone < 0) {
    const Blocks& bl = m.blocks;
    const double c = std::cos(bl.rotation[t.block]), s = std::sin(bl.rotation[t.block]);
    h.arm = rotated(t.local, c, s);
    h.position = bl.centroid[t.block] + h.arm;
    h.velocity = bl.velocity[t.block] + bl.angularVelocity[t.block] * Vec2{-h.arm.y, h.arm.x};
    h.centre = bl.centroid[t.block];
    return h;
  }
  const Gridpoints& g = m.gridpoints;
  for (int k = 0; k < 3; ++k) {
    const int p = m.zones.gridpoint[t.zone][k];
    h.position += t.weight[k] * g.position[p];
    h.velocity += t.weight[k] * g.velocity[p];
    h.centre += (1.0 / 3.0) * g.position[p];
  }
  return h;
}

}  // namespace

BeamStepTotals computeBeamForces(Model& m, double dt) {
  BeamStepTotals totals;
  Structures& st = m.structures;
  BeamNodes& nd = st.nodes;
  BeamElements& el = st.elements;
  std::fill(nd.force.begin(), nd.force.end(), Vec2{});
  std::fill(nd.moment.begin(), nd.moment.end(), 0.0);
  std::fill(nd.forceScale.begin(), nd.forceScale.end(), 0.0);
  for (int e = 0; e < el.size(); ++e) {
    const BeamMaterial& mat = st.materials[st.beams[el.beam[e]].material];
    const int a = el.node[e][0], b = el.node[e][1];
    const Vec2 d = nd.position[b] - nd.position[a];
    const double length = norm(d), rest = el.restLength[e];
    const Vec2 along = (1.0 / length) * d, across{-along.y, along.x};
    // Co-rotational: the chord's rotation carries the element; what is left of each node's
    // rotation bends it, small against the chord.
    const double chord = wrapped(std::atan2(d.y, d.x) - el.restAngle[e]);
    const double bendA = wrapped(nd.rotation[a] - chord), bendB = wrapped(nd.rotation[b] - chord);
    const double ea = mat.young * mat.area, ei = mat.young * mat.inertia;
    const double axial = ea * (length - rest) / rest;
    const double momentA = (ei / rest) * (4.0 * bendA + 2.0 * bendB), momentB = (ei / rest) * (2.0 * bendA + 4.0 * bendB);
    const double shear = (momentA + momentB) / length;
    // The forces are minus the strain energy's gradient: dL = along . (dxB - dxA), the chord
    // turns by across . (dxB - dxA) / L, and each bend by its node's rotation less that.
    nd.force[a] += axial * along - shear * across;
    nd.force[b] -= axial * along - shear * across;
    nd.moment[a] -= momentA;
    nd.moment[b] -= momentB;
    const double size = std::hypot(axial, shear);
    nd.forceScale[a] += size;
    nd.forceScale[b] += size;
    el.axialForce[e] = axial;
    el.shearForce[e] = shear;
    // Bending moments E I kappa at the ends (kappa the curvature along node 0 -> node 1, positive
    // bending counter-clockwise): the cubic's w''(0) L = -(4 a + 2 b), w''(L) L = 2 a + 4 b.
    el.endMoment[e] = {-momentA, momentB};
    totals.strainEnergy += 0.5 * axial * (length - rest) + (ei / rest) * (2.0 * bendA * bendA + 2.0 * bendA * bendB + 2.0 * bendB * bendB);
  }
  std::fill(nd.tieForce.begin(), nd.tieForce.end(), Vec2{});
  for (BeamTie& t : st.ties) {
    if (t.broken) continue;
    const HostPoint host = hostPoint(m, t);
    const Vec2 s = nodeTangent(m, t.node), n{-s.y, s.x};
    const Vec2 step = dt * (nd.velocity[t.node] - host.velocity);
    double fn = dot(t.force, n) - t.normalStiffness * dot(step, n);
    double fs = dot(t.force, s) - t.shearStiffness * dot(step, s);
    // Compression: the rock pushing the node away from itself.
    const double side = dot(host.centre - nd.position[t.node], n) >= 0.0 ? 1.0 : -1.0;
    const double compression = -side * fn;
    if (compression < -t.tension) {
      t.broken = true;
      t.force = {};
      continue;
    }
    const double strength = t.cohesion + t.friction * std::max(compression, 0.0);
    t.slipping = std::abs(fs) > strength;
    if (t.slipping) fs = fs > 0.0 ? strength : -strength;
    t.force = fn * n + fs * s;
    nd.tieForce[t.node] += t.force;
    if (t.zone < 0) {
      m.blocks.boundaryForce[t.block] -= t.force;
      m.blocks.boundaryMoment[t.block] -= cross(host.arm, t.force);
    } else {
      for (int k = 0; k < 3; ++k) m.gridpoints.tractionForce[m.zones.gridpoint[t.zone][k]] -= t.weight[k] * t.force;
    }
  }
  return totals;
}

MotionStepTotals integrateBeamNodes(Model& m, double dt, double alpha, double local) {
  MotionStepTotals totals;
  BeamNodes& nd = m.structures.nodes;
  const double lose = 1.0 - 0.5 * alpha * dt, keep = 1.0 / (1.0 + 0.5 * alpha * dt);
  // One degree of freedom, as the rigid blocks' (1.3-21). The elements' forces are internal
  // (their strain energy is counted); gravity, loads and the ties' forces do external work (the
  // ties' springs and slip are thus in the work done on the nodes and on the rock together).
  auto advance = [&](bool held, double v0, double inertia, double internal, double body, double& unbalanced) {
    if (held) return 0.0;
    const double load = internal + body;
    unbalanced += load * load;
    const double damping = localDampingForce(local, load, v0);
    const double v1 = keep * (lose * v0 + (dt / inertia) * (load + damping));
    const double vbar = 0.5 * (v0 + v1);
    totals.kineticEnergy += 0.25 * inertia * (v0 * v0 + v1 * v1);
    totals.kineticLag += 0.5 * inertia * v0 * v1;
    totals.dampingDissipation += alpha * inertia * vbar * vbar * dt - damping * vbar * dt;
    totals.dampingPower += inertia * vbar * vbar;
    totals.kineticRate += inertia * vbar * (v1 - v0) / dt;
    totals.externalWork += body * v1 * dt;
    return v1;
  };
  for (int i = 0; i < nd.size(); ++i) {
    const Vec2 body = nd.mass[i] * m.gravity + nd.appliedForce[i] + nd.tieForce[i];
    double unbalanced = 0.0;
    const Vec2 v{advance(nd.fixed[i] & DriveX, nd.velocity[i].x, nd.mass[i], nd.force[i].x, body.x, unbalanced),
                 advance(nd.fixed[i] & DriveY, nd.velocity[i].y, nd.mass[i], nd.force[i].y, body.y, unbalanced)};
    double momentUnbalanced = 0.0;  // kept apart from the forces, as the rigid blocks' moments
    const double w = advance(nd.fixed[i] & DriveRotation, nd.angularVelocity[i], nd.rotaryInertia[i], nd.moment[i],
                             nd.appliedMoment[i], momentUnbalanced);
    totals.largestUnbalancedForce = std::max(totals.largestUnbalancedForce, std::sqrt(unbalanced));
    totals.forceScaleSum += nd.forceScale[i] + norm(nd.tieForce[i]);
    ++totals.forceCount;
    nd.velocity[i] = v;
    nd.angularVelocity[i] = w;
    nd.position[i] += dt * v;
    nd.rotation[i] += dt * w;
    totals.largestDisplacement = std::max(totals.largestDisplacement, norm(v) * dt);
  }
  return totals;
}

double beamTimeStep(const Model& m, double frac, double zoneFraction) {
  const Structures& st = m.structures;
  const BeamNodes& nd = st.nodes;
  const BeamElements& el = st.elements;
  // Gershgorin's bound on the largest eigenvalue of M^-1/2 K M^-1/2, row by row: a translation
  // row takes (EA/L + 12 EI/L^3 + |N|/L) for each node's pair of translations and 6 EI/L^2 for
  // each rotation (a bound for one element in any direction; where two elements meet at an angle
  // the true row sum can exceed it, by up to 1.21 times EA/L at 22.5 degrees, which the 0.9 below
  // covers); a rotation row 4 EI/L, 2 EI/L and 6 EI/L^2 for each translation.
  std::vector<double> translation(nd.size(), 0.0), rotation(nd.size(), 0.0);
  for (int e = 0; e < el.size(); ++e) {
    const BeamMaterial& mat = st.materials[st.beams[el.beam[e]].material];
    const double length = el.restLength[e];
    const double ei = mat.young * mat.inertia;
    const double lateral = mat.young * mat.area / length + 12.0 * ei / (length * length * length) + std::abs(el.axialForce[e]) / length;
    const double coupling = 6.0 * ei / (length * length), turning = 4.0 * ei / length, carried = 2.0 * ei / length;
    for (int end = 0; end < 2; ++end) {
      const int i = el.node[e][end], j = el.node[e][1 - end];
      const double mi = nd.mass[i], mj = nd.mass[j], ji = nd.rotaryInertia[i], jj = nd.rotaryInertia[j];
      translation[i] += lateral / mi + lateral / std::sqrt(mi * mj) + coupling / std::sqrt(mi * ji) + coupling / std::sqrt(mi * jj);
      rotation[i] += turning / ji + carried / std::sqrt(ji * jj) + std::numbers::sqrt2 * coupling * (1.0 / std::sqrt(ji * mi) + 1.0 / std::sqrt(ji * mj));
    }
  }
  std::vector<double> blockStiffness(m.blocks.size(), 0.0), pointStiffness(m.gridpoints.size(), 0.0);
  for (const BeamTie& t : st.ties) {
    const double k = t.normalStiffness + t.shearStiffness;
    translation[t.node] += k / nd.mass[t.node];
    if (t.zone < 0) blockStiffness[t.block] += k;
    else
      for (int c = 0; c < 3; ++c) pointStiffness[m.zones.gridpoint[t.zone][c]] += t.weight[c] * k;
  }
  double largest = 0.0;
  for (int i = 0; i < nd.size(); ++i) largest = std::max({largest, translation[i], rotation[i]});
  // 0.9 of the bound, for what it leaves out: the ties' rock moving too, a chord turning fast.
  double dt = largest > 0.0 ? 0.9 * 2.0 / std::sqrt(largest) : INFINITY;
  for (int b = 0; b < m.blocks.size(); ++b)
    if (blockStiffness[b] > 0.0 && m.blocks.movesFreely(b)) dt = std::min(dt, frac * 2.0 * std::sqrt(m.blocks.mass[b] / blockStiffness[b]));
  for (int i = 0; i < m.gridpoints.size(); ++i)
    if (pointStiffness[i] > 0.0)
      dt = std::min(dt, zoneFraction * 2.0 * std::sqrt(m.gridpoints.mass[i] / (m.gridpoints.stiffness[i] + pointStiffness[i])));
  return dt;
}

}  // namespace vdec
