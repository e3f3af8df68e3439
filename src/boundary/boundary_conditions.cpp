#include "boundary/boundary_conditions.hpp"

#include <algorithm>

namespace vdec {

double addBoundaryCondition(Model& m, BoundaryCondition condition, double timeOrigin) {
  const int source = static_cast<int>(m.boundaryConditions.size());
  Gridpoints& g = m.gridpoints;
  double taken = 0.0;
  for (const int i : condition.gridpoints) {
    const Vec2 before = g.velocity[i];
    g.driven[i] |= condition.fix | condition.velocityBits;
    if (condition.fix & DriveX) g.velocity[i].x = 0.0;
    if (condition.fix & DriveY) g.velocity[i].y = 0.0;
    if (condition.velocityBits & DriveX) g.velocity[i].x = condition.velocity.x;
    if (condition.velocityBits & DriveY) g.velocity[i].y = condition.velocity.y;
    // Before the run the masses are not yet formed (and nothing moves).
    const double mass = i < static_cast<int>(g.mass.size()) ? g.mass[i] : 0.0;
    taken += 0.5 * mass * (dot(before, before) - dot(g.velocity[i], g.velocity[i]));
    if (condition.history < 0) continue;
    if (condition.velocityBits & DriveX)
      m.drivenVelocities.push_back({i, 0, condition.velocity.x, condition.history, timeOrigin, source});
    if (condition.velocityBits & DriveY)
      m.drivenVelocities.push_back({i, 1, condition.velocity.y, condition.history, timeOrigin, source});
  }
  for (ViscousEdge e : condition.dashpots) {
    e.source = source;
    e.timeOrigin = timeOrigin;
    m.viscousEdges.push_back(e);
  }
  for (RigidViscousEdge e : condition.rigidDashpots) {
    e.source = source;
    e.timeOrigin = timeOrigin;
    m.rigidViscousEdges.push_back(e);
  }
  if (!m.rigidViscousEdges.empty()) {
    Blocks& bl = m.blocks;
    bl.dashpotForce.resize(bl.size());
    bl.dashpotMoment.resize(bl.size());
    bl.boundaryForce.resize(bl.size());
    bl.boundaryMoment.resize(bl.size());
  }
  for (FreeFieldColumn c : condition.freeField) {
    c.source = source;
    c.timeOrigin = timeOrigin;
    m.freeFields.push_back(std::move(c));
  }
  if (!m.viscousEdges.empty() || !m.freeFields.empty()) g.dashpotForce.resize(g.size());
  for (LoadedEdge e : condition.edges) {
    e.timeOrigin = timeOrigin;
    e.source = source;
    m.loadedEdges.push_back(e);
  }
  m.boundaryConditions.push_back(std::move(condition));
  return taken;
}

double freeBoundaryCondition(Model& m, const std::string& name) {
  const auto found = std::find_if(m.boundaryConditions.begin(), m.boundaryConditions.end(),
                                  [&](const BoundaryCondition& b) { return b.active && !name.empty() && b.name == name; });
  if (found == m.boundaryConditions.end()) return 0.0;
  found->active = false;
  const int source = static_cast<int>(found - m.boundaryConditions.begin());
  std::erase_if(m.loadedEdges, [source](const LoadedEdge& e) { return e.source == source; });
  std::erase_if(m.drivenVelocities, [source](const DrivenVelocity& d) { return d.source == source; });
  std::erase_if(m.viscousEdges, [source](const ViscousEdge& e) { return e.source == source; });
  std::erase_if(m.rigidViscousEdges, [source](const RigidViscousEdge& e) { return e.source == source; });
  std::erase_if(m.freeFields, [source](const FreeFieldColumn& c) { return c.source == source; });
  Gridpoints& g = m.gridpoints;
  std::vector<std::uint8_t> before;
  for (const int i : found->gridpoints) before.push_back(g.driven[i]);
  for (const int i : found->gridpoints) g.driven[i] = (g.driven[i] & Excavated) ? DriveX | DriveY | Excavated : 0;
  for (const BoundaryCondition& b : m.boundaryConditions)
    if (b.active)
      for (const int i : b.gridpoints) g.driven[i] |= b.fix | b.velocityBits;
  // A component set free keeps its velocity: kinetic energy the motion account had not counted.
  double released = 0.0;
  for (std::size_t k = 0; k < found->gridpoints.size(); ++k) {
    const int i = found->gridpoints[k];
    const std::uint8_t freed = before[k] & ~g.driven[i];
    const Vec2 v = g.velocity[i];
    if (freed & DriveX) released += 0.5 * g.mass[i] * v.x * v.x;
    if (freed & DriveY) released += 0.5 * g.mass[i] * v.y * v.y;
  }
  return released;
}

}  // namespace vdec
