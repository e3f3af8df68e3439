#include "structure/beams.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "core/errors.hpp"
#include "core/shown.hpp"
#include "structure/lumped_motion.hpp"
#include "structure/rock_point.hpp"

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

// An element's forces from its nodes' positions and rotations, co-rotational: the chord's rotation
// carries the element; what is left of each node's rotation bends it, small against the chord.
struct ElementState {
  Vec2 along, across;
  double axial = 0.0, shear = 0.0, momentA = 0.0, momentB = 0.0, strainEnergy = 0.0;
};

ElementState elementState(const Model& m, int e) {
  const Structures& st = m.structures;
  const BeamNodes& nd = st.nodes;
  const BeamElements& el = st.elements;
  const BeamMaterial& mat = st.materials[st.beams[el.beam[e]].material];
  const int a = el.node[e][0], b = el.node[e][1];
  const Vec2 d = nd.position[b] - nd.position[a];
  const double length = norm(d), rest = el.restLength[e];
  ElementState f;
  f.along = (1.0 / length) * d;
  f.across = {-f.along.y, f.along.x};
  const double chord = wrapped(std::atan2(d.y, d.x) - el.restAngle[e]);
  const double bendA = wrapped(nd.rotation[a] - chord), bendB = wrapped(nd.rotation[b] - chord);
  const double ea = mat.young * mat.area, ei = mat.young * mat.inertia;
  f.axial = ea * (length - rest) / rest;
  f.momentA = (ei / rest) * (4.0 * bendA + 2.0 * bendB);
  f.momentB = (ei / rest) * (2.0 * bendA + 4.0 * bendB);
  // The forces are minus the strain energy's gradient: dL = along . (dxB - dxA), the chord
  // turns by across . (dxB - dxA) / L, and each bend by its node's rotation less that.
  f.shear = (f.momentA + f.momentB) / length;
  f.strainEnergy = 0.5 * f.axial * (length - rest) + (ei / rest) * (2.0 * bendA * bendA + 2.0 * bendA * bendB + 2.0 * bendB * bendB);
  return f;
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
    if (!st.beams[el.beam[e]].installed) continue;
    const int a = el.node[e][0], b = el.node[e][1];
    const ElementState f = elementState(m, e);
    nd.force[a] += f.axial * f.along - f.shear * f.across;
    nd.force[b] -= f.axial * f.along - f.shear * f.across;
    nd.moment[a] -= f.momentA;
    nd.moment[b] -= f.momentB;
    const double size = std::hypot(f.axial, f.shear);
    nd.forceScale[a] += size;
    nd.forceScale[b] += size;
    el.axialForce[e] = f.axial;
    el.shearForce[e] = f.shear;
    // Bending moments E I kappa at the ends (kappa the curvature along node 0 -> node 1, positive
    // bending counter-clockwise): the cubic's w''(0) L = -(4 a + 2 b), w''(L) L = 2 a + 4 b.
    el.endMoment[e] = {-f.momentA, f.momentB};
    totals.strainEnergy += f.strainEnergy;
  }
  std::fill(nd.tieForce.begin(), nd.tieForce.end(), Vec2{});
  for (BeamTie& t : st.ties) {
    if (t.broken) continue;
    const RockPointNow host = rockPointNow(m, t);
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
    loadRock(m, t, host, -t.force);
  }
  return totals;
}

MotionStepTotals integrateBeamNodes(Model& m, double dt, double alpha, double local) {
  MotionStepTotals totals;
  BeamNodes& nd = m.structures.nodes;
  // One degree of freedom at a time. The elements' forces are internal (their strain energy is
  // counted); gravity, loads and the ties' forces do external work (the ties' springs and slip
  // are thus in the work done on the nodes and on the rock together).
  auto advance = [&](bool held, double v0, double inertia, double internal, double body, double& unbalanced) {
    if (held) return 0.0;
    unbalanced += (internal + body) * (internal + body);
    return advanceLumped(totals, v0, inertia, internal, body, alpha, local, dt);
  };
  for (int i = 0; i < nd.size(); ++i) {
    if (!m.structures.beams[nd.beam[i]].installed) continue;
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
    if (!st.beams[el.beam[e]].installed) continue;
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
  HostStiffness hosts(m);
  for (const BeamTie& t : st.ties) {
    const double k = t.normalStiffness + t.shearStiffness;
    translation[t.node] += k / nd.mass[t.node];
    hosts.add(m, t, k);
  }
  double largest = 0.0;
  for (int i = 0; i < nd.size(); ++i) largest = std::max({largest, translation[i], rotation[i]});  // 0 where not installed
  // 0.9 of the bound, for what it leaves out: the ties' rock moving too, a chord turning fast.
  const double dt = largest > 0.0 ? 0.9 * 2.0 / std::sqrt(largest) : INFINITY;
  return std::min(dt, hosts.timeStep(m, frac, zoneFraction));
}

void installBeam(Model& m, int index, const std::string& when) {
  Structures& st = m.structures;
  Beam& beam = st.beams[index];
  BeamNodes& nd = st.nodes;
  BeamElements& el = st.elements;
  const BeamMaterial& mat = st.materials[beam.material];
  for (int n = beam.firstNode; n < beam.firstNode + beam.nodeCount; ++n) {
    nd.velocity[n] = {};
    nd.angularVelocity[n] = 0.0;
    nd.rotation[n] = 0.0;
    if (!beam.tied) continue;
    const Vec2 point = nd.initialPosition[n];
    BeamTie t;
    const double distance = findRockPoint(m, point, t);
    if (!(distance <= m.roundingLength))
      throw SceneError((when.empty() ? "" : when + ": ") + "beam '" + beam.name + "': its node at (" + shown(point.x) + ", " + shown(point.y) +
                       ") lies on no block (the nearest is " + shown(distance) + " m away, beyond the rounding length): "
                       "place the beam on the rock, or set tied = false");
    t.node = n;
    t.normalStiffness = mat.tieNormalStiffness * nd.length[n];
    t.shearStiffness = mat.tieShearStiffness * nd.length[n];
    t.cohesion = mat.tieCohesion * nd.length[n];
    t.friction = mat.tieFriction;
    t.tension = mat.tieTension * nd.length[n];
    // Installed where the rock is now: the node on its host's point as the rock has moved.
    nd.position[n] = rockPointNow(m, t).position;
    st.ties.push_back(t);
  }
  // Stress-free as placed.
  for (int e = beam.firstElement; e < beam.firstElement + beam.elementCount; ++e) {
    const Vec2 chord = nd.position[el.node[e][1]] - nd.position[el.node[e][0]];
    el.restLength[e] = norm(chord);
    el.restAngle[e] = std::atan2(chord.y, chord.x);
    el.axialForce[e] = el.shearForce[e] = 0.0;
    el.endMoment[e] = {0.0, 0.0};
  }
  for (int n = beam.firstNode; n < beam.firstNode + beam.nodeCount; ++n) nd.initialPosition[n] = nd.position[n];
  if (!st.ties.empty()) {
    m.blocks.boundaryForce.resize(m.blocks.size());
    m.blocks.boundaryMoment.resize(m.blocks.size());
  }
  beam.installed = true;
}

double removeBeam(Model& m, int index) {
  Structures& st = m.structures;
  Beam& beam = st.beams[index];
  BeamNodes& nd = st.nodes;
  double energy = 0.0;
  for (int e = beam.firstElement; e < beam.firstElement + beam.elementCount; ++e) energy += elementState(m, e).strainEnergy;
  for (int n = beam.firstNode; n < beam.firstNode + beam.nodeCount; ++n) {
    energy += 0.5 * (nd.mass[n] * dot(nd.velocity[n], nd.velocity[n]) +
                     nd.rotaryInertia[n] * nd.angularVelocity[n] * nd.angularVelocity[n]);
    nd.velocity[n] = {};
    nd.angularVelocity[n] = 0.0;
  }
  for (BeamTie& t : st.ties)
    if (nd.beam[t.node] == index) {
      t.broken = true;
      t.force = {};
    }
  beam.installed = false;
  return energy;
}

}  // namespace vdec
