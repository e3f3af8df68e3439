#pragma once
// A point of the rock that a support holds: fixed in a rigid block's frame, or at barycentric
// weights in a zone. Where it is and how it moves now, and the load a support puts on it. `Held`
// is any record with the fields block, local, zone and weight (a beam's tie, a cable node's grout).
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "core/model.hpp"
#include "geometry/polygon.hpp"

namespace vdec {

struct RockPointNow {
  Vec2 position, velocity, centre, arm;  // centre: the host's (block centroid, zone centroid); arm: from the centroid
};

template <class Held>
RockPointNow rockPointNow(const Model& m, const Held& held) {
  RockPointNow now;
  if (held.zone < 0) {
    const Blocks& bl = m.blocks;
    const double c = std::cos(bl.rotation[held.block]), s = std::sin(bl.rotation[held.block]);
    now.arm = rotated(held.local, c, s);
    now.position = bl.centroid[held.block] + now.arm;
    now.velocity = bl.velocity[held.block] + bl.angularVelocity[held.block] * Vec2{-now.arm.y, now.arm.x};
    now.centre = bl.centroid[held.block];
    return now;
  }
  const Gridpoints& g = m.gridpoints;
  for (int k = 0; k < 3; ++k) {
    const int p = m.zones.gridpoint[held.zone][k];
    now.position += held.weight[k] * g.position[p];
    now.velocity += held.weight[k] * g.velocity[p];
    now.centre += (1.0 / 3.0) * g.position[p];
  }
  return now;
}

// `force` on the rock at the held point: a rigid block's boundary force and moment, or the zone's
// gridpoints' traction forces by the point's weights.
template <class Held>
void loadRock(Model& m, const Held& held, const RockPointNow& now, Vec2 force) {
  if (held.zone < 0) {
    m.blocks.boundaryForce[held.block] += force;
    m.blocks.boundaryMoment[held.block] += cross(now.arm, force);
    return;
  }
  for (int k = 0; k < 3; ++k) m.gridpoints.tractionForce[m.zones.gridpoint[held.zone][k]] += held.weight[k] * force;
}

// The stiffness supports add to the rock they hold, and the step that leaves that rock: a free
// rigid block frac 2 sqrt(m / k) (1.3-28), a gridpoint zoneFraction 2 sqrt(m / (k_own + k)) (1.3-25).
class HostStiffness {
 public:
  explicit HostStiffness(const Model& m) : block_(m.blocks.size(), 0.0), point_(m.gridpoints.size(), 0.0) {}
  template <class Held>
  void add(const Model& m, const Held& held, double k) {
    if (held.zone < 0) block_[held.block] += k;
    else
      for (int c = 0; c < 3; ++c) point_[m.zones.gridpoint[held.zone][c]] += held.weight[c] * k;
  }
  double timeStep(const Model& m, double frac, double zoneFraction) const {
    double dt = INFINITY;
    for (int b = 0; b < m.blocks.size(); ++b)
      if (block_[b] > 0.0 && m.blocks.movesFreely(b)) dt = std::min(dt, frac * 2.0 * std::sqrt(m.blocks.mass[b] / block_[b]));
    for (int i = 0; i < m.gridpoints.size(); ++i)
      if (point_[i] > 0.0)
        dt = std::min(dt, zoneFraction * 2.0 * std::sqrt(m.gridpoints.mass[i] / (m.gridpoints.stiffness[i] + point_[i])));
    return dt;
  }

 private:
  std::vector<double> block_, point_;
};

namespace rock_point_detail {

inline double segmentDistance(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 d = b - a;
  const double t = std::clamp(dot(p - a, d) / dot(d, d), 0.0, 1.0);
  return norm(p - (a + t * d));
}

// Distance from a point to a triangle (0 inside) and the point's barycentric weights, clamped to it.
inline double triangleDistance(Vec2 p, const std::array<Vec2, 3>& v, std::array<double, 3>& weight) {
  const double area = cross(v[1] - v[0], v[2] - v[0]);
  for (int k = 0; k < 3; ++k) weight[k] = cross(v[(k + 1) % 3] - p, v[(k + 2) % 3] - p) / area;
  if (weight[0] >= 0.0 && weight[1] >= 0.0 && weight[2] >= 0.0) return 0.0;
  double best = INFINITY;
  for (int k = 0; k < 3; ++k) best = std::min(best, segmentDistance(p, v[k], v[(k + 1) % 3]));
  double sum = 0.0;
  for (double& w : weight) sum += (w = std::max(w, 0.0));
  for (double& w : weight) w /= sum;
  return best;
}

}  // namespace rock_point_detail

// The rock a point of the reference configuration (the input, or the last displacement reset)
// belongs to: the zone (deformable block) or rigid block holding it, else the nearest. Excavated
// rock is none. Fills held's block, local, zone and weight; returns the distance (infinite: none).
template <class Held>
double findRockPoint(const Model& m, Vec2 point, Held& held) {
  using rock_point_detail::segmentDistance;
  double nearest = INFINITY;
  const Blocks& bl = m.blocks;
  for (int b = 0; b < bl.size(); ++b) {
    if (bl.deformable[b] || bl.excavated(b)) continue;
    Polygon p;
    const int first = bl.firstVertex[b], last = first + bl.vertexCount[b];
    for (int v = first; v < last; ++v) p.push_back(bl.initialCentroid[b] + m.vertices.localPosition[v]);
    double distance = containsPoint(p, point) ? 0.0 : INFINITY;
    for (int v = 0; distance > 0.0 && v < static_cast<int>(p.size()); ++v)
      distance = std::min(distance, segmentDistance(point, p[v], p[(v + 1) % p.size()]));
    if (distance < nearest) {
      nearest = distance;
      held.block = b;
      held.local = point - bl.initialCentroid[b];
      held.zone = -1;
    }
  }
  for (int z = 0; z < m.zones.size(); ++z) {
    std::array<Vec2, 3> corner;
    for (int k = 0; k < 3; ++k) corner[k] = m.gridpoints.initialPosition[m.zones.gridpoint[z][k]];
    std::array<double, 3> weight;
    const double distance = rock_point_detail::triangleDistance(point, corner, weight);
    if (distance < nearest) {
      nearest = distance;
      held.block = m.zones.block[z];
      held.zone = z;
      held.weight = weight;
    }
  }
  return nearest;
}

}  // namespace vdec
