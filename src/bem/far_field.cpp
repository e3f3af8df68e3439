#include "bem/far_field.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace vdec {

namespace {

// A rigid block's vertex from its centroid now.
Vec2 vertexArm(const Model& m, int v) {
  const int b = m.vertices.block[v];
  return rotated(m.vertices.localPosition[v], std::cos(m.blocks.rotation[b]), std::sin(m.blocks.rotation[b]));
}

Vec2 memberPosition(const Model& m, const BoundaryElementField& be, int k) {
  if (be.memberGridpoint[k] >= 0) return m.gridpoints.position[be.memberGridpoint[k]];
  const int v = be.memberVertex[k];
  return m.blocks.centroid[m.vertices.block[v]] + vertexArm(m, v);
}

Vec2 meanPosition(const Model& m, const BoundaryElementField& be, int i) {
  Vec2 sum;
  for (int k = be.firstMember[i]; k < be.firstMember[i + 1]; ++k) sum += be.memberWeight[k] * memberPosition(m, be, k);
  return sum;
}

}  // namespace

void holdPresentStress(Model& m) {
  BoundaryElementField& be = m.boundaryElements;
  for (int i = 0; i < be.size(); ++i) be.node[i] = meanPosition(m, be, i);
  std::map<std::pair<int, int>, int> zoneOfEdge;
  for (int z = 0; z < m.zones.size(); ++z)
    for (int c = 0; c < 3; ++c) zoneOfEdge[{m.zones.gridpoint[z][c], m.zones.gridpoint[z][(c + 1) % 3]}] = z;
  be.memberInitialForce.assign(be.memberGridpoint.size(), {});
  be.force.assign(static_cast<std::size_t>(be.size()), {});
  bool rigid = false;
  for (std::size_t k = 0; k < be.edge.size(); ++k) {
    const Vec2 a = memberPosition(m, be, be.edgeMember[k][0]), b = memberPosition(m, be, be.edgeMember[k][1]);
    double sxx, syy, sxy;
    if (be.edge[k][0] < 0) {
      rigid = true;
      const Vec2 mid = 0.5 * (a + b);
      sxx = be.inSitu[0] + be.inSituGradientX[0] * mid.x + be.inSituGradientY[0] * mid.y;
      syy = be.inSitu[1] + be.inSituGradientX[1] * mid.x + be.inSituGradientY[1] * mid.y;
      sxy = be.inSitu[2] + be.inSituGradientX[2] * mid.x + be.inSituGradientY[2] * mid.y;
    } else {
      const auto zone = zoneOfEdge.find({be.edge[k][0], be.edge[k][1]});
      if (zone == zoneOfEdge.end()) continue;  // dug out: the region meets no rock there
      sxx = m.zones.sxx[zone->second];
      syy = m.zones.syy[zone->second];
      sxy = m.zones.sxy[zone->second];
    }
    const Vec2 outward{b.y - a.y, a.x - b.x};  // a counter-clockwise outline's (d.y, -d.x), times the length
    const Vec2 force{sxx * outward.x + sxy * outward.y, sxy * outward.x + syy * outward.y};
    be.memberInitialForce[be.edgeMember[k][0]] += 0.5 * force;
    be.memberInitialForce[be.edgeMember[k][1]] += 0.5 * force;
  }
  if (rigid) {
    m.blocks.boundaryForce.resize(m.blocks.size());
    m.blocks.boundaryMoment.resize(m.blocks.size());
  }
  be.on = true;
}

Vec2 boundaryElementNodeDisplacement(const Model& m, int i) {
  const BoundaryElementField& be = m.boundaryElements;
  return meanPosition(m, be, i) - be.node[i];
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
    double fx = 0.0, fy = 0.0;
    const double* rowX = K + static_cast<std::size_t>(2 * i) * (2 * n);
    const double* rowY = rowX + 2 * n;
    for (int j = 0; j < 2 * n; ++j) {
      fx -= rowX[j] * u[j];
      fy -= rowY[j] * u[j];
    }
    const Vec2 response{fx, fy};
    be.force[i] = {};
    for (int k = be.firstMember[i]; k < be.firstMember[i + 1]; ++k) {
      const Vec2 f = be.memberInitialForce[k] + be.memberWeight[k] * response;
      be.force[i] += f;
      if (be.memberGridpoint[k] >= 0) {
        m.gridpoints.tractionForce[be.memberGridpoint[k]] += f;
        continue;
      }
      const int v = be.memberVertex[k], b = m.vertices.block[v];
      if (m.blocks.excavated(b)) continue;  // dug out: the region meets no rock there
      m.blocks.boundaryForce[b] += f;
      m.blocks.boundaryMoment[b] += cross(vertexArm(m, v), f);
    }
  }
}

double boundaryElementTimeStep(const Model& m, double frac, double zoneFraction) {
  const BoundaryElementField& be = m.boundaryElements;
  const int n = be.size();
  const Gridpoints& g = m.gridpoints;
  double dt = INFINITY;
  // What the region adds to its rigid blocks' stiffness, in translation and in rotation.
  std::map<int, std::pair<double, double>> blockStiffness;
  for (int i = 0; i < n; ++i) {
    // A node's rows of K bound what the region adds to its points' stiffness; a point moves its
    // node by its weight and takes that share of the response.
    double row = 0.0;
    for (int r = 0; r < 2; ++r) {
      double sum = 0.0;
      for (int j = 0; j < 2 * n; ++j) sum += std::abs(be.stiffness[static_cast<std::size_t>(2 * i + r) * (2 * n) + j]);
      row = std::max(row, sum);
    }
    for (int k = be.firstMember[i]; k < be.firstMember[i + 1]; ++k) {
      const double share = be.memberWeight[k];
      if (be.memberGridpoint[k] >= 0) {
        const int p = be.memberGridpoint[k];
        dt = std::min(dt, zoneFraction * 2.0 * std::sqrt(g.mass[p] / (g.stiffness[p] + share * row)));
        continue;
      }
      const int v = be.memberVertex[k];
      auto& [translation, rotation] = blockStiffness[m.vertices.block[v]];
      translation += share * row;
      rotation += share * row * dot(vertexArm(m, v), vertexArm(m, v));
    }
  }
  // 1.3-28 with the region's stiffness on each free block, in translation and in rotation, beside
  // the joints' limit of the rigid-block component (frac keeps the margin for their sum).
  for (const auto& [b, k] : blockStiffness) {
    if (!m.blocks.movesFreely(b)) continue;
    dt = std::min(dt, frac * 2.0 * std::sqrt(m.blocks.mass[b] / k.first));
    if (k.second > 0.0) dt = std::min(dt, frac * 2.0 * std::sqrt(m.blocks.inertia[b] / k.second));
  }
  return dt;
}

}  // namespace vdec
