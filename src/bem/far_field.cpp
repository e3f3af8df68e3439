#include "bem/far_field.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace vdec {

void holdPresentStress(Model& m) {
  BoundaryElementField& be = m.boundaryElements;
  const Gridpoints& g = m.gridpoints;
  for (int i = 0; i < be.size(); ++i) {
    Vec2 sum;
    for (int k = be.firstGridpoint[i]; k < be.firstGridpoint[i + 1]; ++k) sum += g.position[be.gridpoints[k]];
    be.node[i] = (1.0 / (be.firstGridpoint[i + 1] - be.firstGridpoint[i])) * sum;
  }
  std::map<std::pair<int, int>, int> zoneOfEdge;
  for (int z = 0; z < m.zones.size(); ++z)
    for (int c = 0; c < 3; ++c) zoneOfEdge[{m.zones.gridpoint[z][c], m.zones.gridpoint[z][(c + 1) % 3]}] = z;
  be.initialForce.assign(static_cast<std::size_t>(be.size()), {});
  be.force.assign(static_cast<std::size_t>(be.size()), {});
  for (std::size_t k = 0; k < be.edge.size(); ++k) {
    const auto zone = zoneOfEdge.find({be.edge[k][0], be.edge[k][1]});
    if (zone == zoneOfEdge.end()) continue;  // dug out: the region meets no rock there
    const int z = zone->second;
    const Vec2 a = g.position[be.edge[k][0]], b = g.position[be.edge[k][1]];
    const Vec2 outward{b.y - a.y, a.x - b.x};  // a counter-clockwise outline's (d.y, -d.x), times the length
    const Vec2 force{m.zones.sxx[z] * outward.x + m.zones.sxy[z] * outward.y,
                     m.zones.sxy[z] * outward.x + m.zones.syy[z] * outward.y};
    be.initialForce[k] += 0.5 * force;
    be.initialForce[(k + 1) % be.node.size()] += 0.5 * force;
  }
  be.on = true;
}

Vec2 boundaryElementNodeDisplacement(const Model& m, int i) {
  const BoundaryElementField& be = m.boundaryElements;
  Vec2 sum;
  const int first = be.firstGridpoint[i], last = be.firstGridpoint[i + 1];
  for (int k = first; k < last; ++k) sum += m.gridpoints.position[be.gridpoints[k]];
  return (1.0 / (last - first)) * sum - be.node[i];
}

void applyBoundaryElementForces(Model& m) {
  BoundaryElementField& be = m.boundaryElements;
  const int n = be.size();
  thread_local std::vector<double> u;  // kept between steps: the stage allocates nothing
  u.resize(2 * static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const Vec2 d = boundaryElementNodeDisplacement(m, i);
    u[2 * i] = d.x;
    u[2 * i + 1] = d.y;
  }
  const double* K = be.stiffness.data();
  for (int i = 0; i < n; ++i) {
    double fx = be.initialForce[i].x, fy = be.initialForce[i].y;
    const double* rowX = K + static_cast<std::size_t>(2 * i) * (2 * n);
    const double* rowY = rowX + 2 * n;
    for (int j = 0; j < 2 * n; ++j) {
      fx -= rowX[j] * u[j];
      fy -= rowY[j] * u[j];
    }
    be.force[i] = {fx, fy};
    const int first = be.firstGridpoint[i], last = be.firstGridpoint[i + 1];
    const double share = 1.0 / (last - first);
    for (int k = first; k < last; ++k) m.gridpoints.tractionForce[be.gridpoints[k]] += share * be.force[i];
  }
}

double boundaryElementTimeStep(const Model& m, double zoneFraction) {
  const BoundaryElementField& be = m.boundaryElements;
  const int n = be.size();
  const Gridpoints& g = m.gridpoints;
  double dt = INFINITY;
  for (int i = 0; i < n; ++i) {
    // A node's rows of K bound what the region adds to its gridpoints' stiffness; a node's
    // displacement is the mean of its gridpoints', so each takes its share squared.
    double row = 0.0;
    for (int r = 0; r < 2; ++r) {
      double sum = 0.0;
      for (int j = 0; j < 2 * n; ++j) sum += std::abs(be.stiffness[static_cast<std::size_t>(2 * i + r) * (2 * n) + j]);
      row = std::max(row, sum);
    }
    const int first = be.firstGridpoint[i], last = be.firstGridpoint[i + 1];
    const double share = 1.0 / (last - first);
    for (int k = first; k < last; ++k) {
      const int p = be.gridpoints[k];
      dt = std::min(dt, zoneFraction * 2.0 * std::sqrt(g.mass[p] / (g.stiffness[p] + share * row)));
    }
  }
  return dt;
}

}  // namespace vdec
