#include "structure/bolts.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/errors.hpp"
#include "core/shown.hpp"
#include "structure/rock_point.hpp"

namespace vdec {

double yieldingSpringForce(double force, double stiffness, double increment, double bound) {
  if (increment == 0.0) return force;
  if (bound == INFINITY) return force + stiffness * increment;
  if (!(bound > 0.0)) return 0.0;
  // With y = 1 - F / F_b the law is dy/dx = -(K / bound) |y| y along x = |d|: y0 / (1 + |y0| K x / bound).
  const double target = increment > 0.0 ? bound : -bound;
  const double y0 = 1.0 - force / target;
  return target * (1.0 - y0 / (1.0 + std::abs(y0) * stiffness * std::abs(increment) / bound));
}

namespace {

// The bound of the shear spring (1.4-40): F_s (1 + s |cos theta0|) / 2, theta0 the bolt's angle to
// the joint, s = +1 when the joint's shear increment stretches the bolt (its sense along the joint
// that of the bolt's own projection on it), -1 when it shortens it, 0 without shear along the joint.
double shearBound(const BoltMaterial& mat, Vec2 direction, Vec2 joint, Vec2 increment) {
  if (mat.shearStrength == INFINITY) return INFINITY;
  const double along = dot(direction, joint), shear = dot(increment, joint);
  const double sense = along * shear > 0.0 ? 1.0 : (along * shear < 0.0 ? -1.0 : 0.0);
  return 0.5 * mat.shearStrength * (1.0 + sense * std::abs(along));
}

}  // namespace

BoltStepTotals computeBoltForces(Model& m, double dt) {
  BoltStepTotals totals;
  Structures& st = m.structures;
  BoltCrossings& x = st.crossings;
  for (int i = 0; i < x.size(); ++i) {
    const Bolt& bolt = st.bolts[x.bolt[i]];
    if (!bolt.installed || x.broken[i]) continue;
    const BoltMaterial& mat = st.boltMaterials[bolt.material];
    const Vec2 e0 = bolt.direction, n0 = perp(e0);
    const RockPointNow rock0 = rockPointNow(m, x.side[i][0]), rock1 = rockPointNow(m, x.side[i][1]);
    const Vec2 du = dt * (rock1.velocity - rock0.velocity);
    // The active length turns with the joint's displacement (Fig. 1.4-16); the axial spring lies
    // along it, the increment taken along its direction midway through the step.
    const Vec2 before = mat.activeLength * e0 + x.displacement[i];
    x.displacement[i] += du;
    const Vec2 after = mat.activeLength * e0 + x.displacement[i];
    const Vec2 axis = normalized(after);
    const Vec2 midway = normalized(normalized(before) + axis);
    const double along = dot(du, midway);
    x.axialDisplacement[i] += along;
    double axialIncrement = along;
    if (mat.crushing) {
      // 1.4-47: the part of the increment due to the turning is reduced by r_f = |u_axial| / |u|.
      const double straight = dot(du, e0), total = norm(x.displacement[i]);
      const double rf = total > 0.0 ? std::min(1.0, std::abs(x.axialDisplacement[i]) / total) : 1.0;
      axialIncrement = straight + rf * (along - straight);
    }
    x.axialForce[i] = yieldingSpringForce(x.axialForce[i], mat.axialStiffness, axialIncrement, mat.axialStrength);
    x.shearForce[i] = yieldingSpringForce(x.shearForce[i], mat.shearStiffness, dot(du, n0),
                                          shearBound(mat, e0, x.jointDirection[i], du));
    // Tension pulls side 1 back towards side 0; the shear spring resists side 1's motion along n0.
    const Vec2 onSide1 = -(x.axialForce[i] * axis + x.shearForce[i] * n0);
    loadRock(m, x.side[i][0], rock0, -onSide1);
    loadRock(m, x.side[i][1], rock1, onSide1);
    totals.sumForceMagnitude += norm(onSide1);
    ++totals.acting;
  }
  return totals;
}

double boltTimeStep(const Model& m, double frac, double zoneFraction) {
  const Structures& st = m.structures;
  const BoltCrossings& x = st.crossings;
  HostStiffness hosts(m);
  for (int i = 0; i < x.size(); ++i) {
    const Bolt& bolt = st.bolts[x.bolt[i]];
    if (!bolt.installed || x.broken[i]) continue;
    const BoltMaterial& mat = st.boltMaterials[bolt.material];
    const double k = mat.axialStiffness + mat.shearStiffness;  // both may push one way
    for (const RockHold& h : x.side[i]) hosts.add(m, h, k);
  }
  return hosts.timeStep(m, frac, zoneFraction);
}

namespace {

struct EdgeHit {
  double t = 0.0;     // along the bolt, 0 at `from`, 1 at `to`
  int vertex = -1;    // the edge from this vertex to the next
  bool leaving = false;  // the bolt leaves the block through it
};

// The point p on the edge from vertex v as a hold of its block: in a rigid block's frame, or in
// the zone of a deformable block that owns the edge (none when that zone is gone).
bool holdAt(const Model& m, int v, Vec2 p, RockHold& hold) {
  const Vertices& vx = m.vertices;
  const int b = vx.block[v];
  const Blocks& bl = m.blocks;
  if (!bl.deformable[b]) {
    const double c = std::cos(bl.rotation[b]), s = std::sin(bl.rotation[b]);
    hold.block = b;
    hold.zone = -1;
    hold.local = rotated(p - bl.centroid[b], c, -s);
    return true;
  }
  const int g0 = vx.gridpoint[v], g1 = vx.gridpoint[vx.next[v]];
  const Gridpoints& g = m.gridpoints;
  const double along = std::clamp(dot(p - g.position[g0], g.position[g1] - g.position[g0]) /
                                      dot(g.position[g1] - g.position[g0], g.position[g1] - g.position[g0]),
                                  0.0, 1.0);
  // (Looked for among the block's zones: installation may come before the gridpoint-to-zone index.)
  for (int z = 0; z < m.zones.size(); ++z) {
    if (m.zones.block[z] != b) continue;
    const auto& corner = m.zones.gridpoint[z];
    const auto at0 = std::find(corner.begin(), corner.end(), g0), at1 = std::find(corner.begin(), corner.end(), g1);
    if (at0 == corner.end() || at1 == corner.end()) continue;
    hold.block = b;
    hold.zone = z;
    hold.weight = {};
    hold.weight[static_cast<std::size_t>(at0 - corner.begin())] = 1.0 - along;
    hold.weight[static_cast<std::size_t>(at1 - corner.begin())] = along;
    return true;
  }
  return false;
}

}  // namespace

void installBolt(Model& m, int index, const std::string& when) {
  Structures& st = m.structures;
  Bolt& bolt = st.bolts[index];
  const Vec2 span = bolt.to - bolt.from;
  const double length = norm(span);
  const Vertices& vx = m.vertices;
  const Blocks& bl = m.blocks;
  std::vector<EdgeHit> hits;
  for (int v = 0; v < vx.size(); ++v) {
    const int b = vx.block[v];
    if (bl.excavated(b)) continue;
    const VertexGeometry& e = vx.geometry[v];
    const Vec2 a = e.position, d = e.edgeLength * e.edgeDirection;
    const double denominator = cross(span, d);
    if (denominator == 0.0) continue;  // parallel: the bolt runs along the edge, crossing nothing there
    const double t = cross(a - bolt.from, d) / denominator, s = cross(a - bolt.from, span) / denominator;
    if (t < 0.0 || t > 1.0 || s < 0.0 || s > 1.0) continue;
    // Counter-clockwise blocks: the outward normal of an edge is its direction turned -90 degrees.
    hits.push_back({t, v, dot(Vec2{e.edgeDirection.y, -e.edgeDirection.x}, bolt.direction) > 0.0});
  }
  std::sort(hits.begin(), hits.end(), [](const EdgeHit& p, const EdgeHit& q) { return p.t < q.t || (p.t == q.t && p.vertex < q.vertex); });
  // Edges met within the rounding length of each other are the two faces of one joint.
  const double reach = std::max(m.roundingLength, 1e-9 * length) / length;
  BoltCrossings& x = st.crossings;
  bolt.firstCrossing = x.size();
  for (std::size_t first = 0; first < hits.size();) {
    std::size_t last = first + 1;
    while (last < hits.size() && hits[last].t - hits[first].t <= reach) ++last;
    const EdgeHit* out = nullptr;
    const EdgeHit* in = nullptr;
    for (std::size_t k = first; k < last; ++k) {
      if (hits[k].leaving && !out) out = &hits[k];
      if (!hits[k].leaving && !in) in = &hits[k];
    }
    first = last;
    if (!out || !in || vx.block[out->vertex] == vx.block[in->vertex]) continue;
    const Vec2 p = bolt.from + (0.5 * (out->t + in->t)) * span;
    std::array<RockHold, 2> side;
    if (!holdAt(m, out->vertex, p, side[0]) || !holdAt(m, in->vertex, p, side[1])) continue;
    x.bolt.push_back(index);
    x.point.push_back(p);
    x.jointDirection.push_back(vx.geometry[out->vertex].edgeDirection);
    x.side.push_back(side);
    x.displacement.push_back({});
    x.axialDisplacement.push_back(0.0);
    x.axialForce.push_back(0.0);
    x.shearForce.push_back(0.0);
    x.broken.push_back(0);
  }
  bolt.crossingCount = x.size() - bolt.firstCrossing;
  if (bolt.crossingCount == 0)
    throw SceneError(when + (when.empty() ? "" : ": ") + "bolt '" + bolt.name + "' from (" + shown(bolt.from.x) + ", " +
                     shown(bolt.from.y) + ") to (" + shown(bolt.to.x) + ", " + shown(bolt.to.y) +
                     ") crosses no joint between two blocks: extend it across a joint");
  m.blocks.boundaryForce.resize(m.blocks.size());
  m.blocks.boundaryMoment.resize(m.blocks.size());
  bolt.installed = true;
}

void breakCrossing(BoltCrossings& x, int i) {
  x.broken[i] = 1;
  x.axialForce[i] = x.shearForce[i] = 0.0;
}

void removeBolt(Model& m, int index) {
  Structures& st = m.structures;
  Bolt& bolt = st.bolts[index];
  bolt.installed = false;
  for (int i = bolt.firstCrossing; i < bolt.firstCrossing + bolt.crossingCount; ++i)
    st.crossings.axialForce[i] = st.crossings.shearForce[i] = 0.0;
}

}  // namespace vdec
