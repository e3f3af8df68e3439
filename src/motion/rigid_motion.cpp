#include "motion/rigid_motion.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "contact/contact_geometry.hpp"
#include "core/errors.hpp"
#include "motion/strain_modes.hpp"

namespace vdec {

void setDrivenVelocities(Model& m, int b, double t) {
  Blocks& bl = m.blocks;
  const int h = bl.velocityHistory[b];
  if (h < 0) return;
  const double scale = m.timeFunctions[h](t);
  const std::uint8_t driven = bl.driven[b];
  if (driven & DriveX) bl.velocity[b].x = scale * bl.inputVelocity[b].x;
  if (driven & DriveY) bl.velocity[b].y = scale * bl.inputVelocity[b].y;
  if (driven & DriveRotation) bl.angularVelocity[b] = scale * bl.inputAngularVelocity[b];
}

MotionStepTotals integrateRigidBlocks(Model& m, double dt, double alpha, double local) {
  MotionStepTotals totals;
  Blocks& bl = m.blocks;
  const double lose = 1.0 - 0.5 * alpha * dt, keep = 1.0 / (1.0 + 0.5 * alpha * dt);
  // One degree of freedom: integrated by 1.3-21 when free, held at its velocity when driven.
  // Returns the new velocity; accumulates kinetic energy, external work and unbalanced force.
  auto advance = [&](bool driven, double v0, double inertia, double contact, double body, double dashpot,
                     double& unbalanced) {
    if (driven) {
      // The driver does work on the rest of the model through the contact force it receives.
      totals.externalWork -= contact * v0 * dt;
      return v0;
    }
    const double load = contact + body + dashpot;
    unbalanced += load * load;
    // 1.3-21: v(t+dt/2) = [v(t-dt/2)(1 - a dt/2) + (F/m + g) dt] / (1 + a dt/2)
    const double damping = localDampingForce(local, load, v0);
    const double v1 = keep * (lose * v0 + (dt / inertia) * (load + damping));
    totals.kineticEnergy += 0.25 * inertia * (v0 * v0 + v1 * v1);
    totals.kineticLag += 0.5 * inertia * v0 * v1;
    // 1.3-21 is m (v1 - v0) / dt = F - alpha m vbar with vbar = (v0 + v1) / 2, so the kinetic
    // energy changes by F vbar dt - alpha m vbar^2 dt: the second term is what damping takes.
    const double vbar = 0.5 * (v0 + v1);
    totals.dampingDissipation += alpha * inertia * vbar * vbar * dt - damping * vbar * dt;
    totals.dampingPower += inertia * vbar * vbar;
    totals.kineticRate += inertia * vbar * (v1 - v0) / dt;
    totals.externalWork += body * v1 * dt;
    totals.boundaryDissipation -= dashpot * vbar * dt;
    return v1;
  };
  for (int b = 0; b < bl.size(); ++b) {
    if (bl.deformable[b]) continue;
    const std::uint8_t driven = bl.driven[b];
    setDrivenVelocities(m, b, m.time + 0.5 * dt);  // v(t + dt/2), of the half step about to be taken
    const double mass = bl.mass[b];
    // Viscous edges: the dashpots' force, and the incoming wave's as a load.
    const bool viscous = !bl.dashpotForce.empty();
    const Vec2 dashpot = viscous ? bl.dashpotForce[b] : Vec2{};
    const double dashpotMoment = viscous ? bl.dashpotMoment[b] : 0.0;
    // Boundary loads: an incoming wave's, fluid pressures.
    const bool loaded = !bl.boundaryForce.empty();
    const Vec2 body = mass * m.gravity + bl.appliedForce[b] + (loaded ? bl.boundaryForce[b] : Vec2{});
    const double bodyMoment = bl.appliedMoment[b] + (loaded ? bl.boundaryMoment[b] : 0.0);
    double unbalanced = 0.0;
    const Vec2 v{advance(driven & DriveX, bl.velocity[b].x, mass, bl.force[b].x, body.x, dashpot.x, unbalanced),
                 advance(driven & DriveY, bl.velocity[b].y, mass, bl.force[b].y, body.y, dashpot.y, unbalanced)};
    if (m.strainModes.holds(b)) {
      // Rotation and strain share a mass matrix: they advance together (a simply-deformable block
      // has no dashpots: the scene refuses viscous boundaries with it).
      bl.velocity[b] = v;
      bl.centroid[b] += dt * v;
      advanceStrainModes(m, b, dt, alpha, local, bodyMoment, unbalanced, totals);
      placeBlockVertices(m, b);
      const StrainModes& s = m.strainModes;
      const Sym2& rate = s.strainRate[s.of[b]];
      const double straining = std::abs(rate.xx) + std::abs(rate.yy) + 2.0 * std::abs(rate.xy);
      totals.largestDisplacement = std::max(totals.largestDisplacement, (norm(v) + (std::abs(bl.angularVelocity[b]) + straining) * bl.boundingRadius[b]) * dt);
      continue;
    }
    double momentUnbalanced = 0.0;
    const double w = advance(driven & DriveRotation, bl.angularVelocity[b], bl.inertia[b], bl.moment[b], bodyMoment,
                             dashpotMoment, momentUnbalanced);
    // The moment counts too, as the force at the block's reach that would make it: a block still
    // turning is not in equilibrium, however small its unbalanced force.
    const double reach = bl.boundingRadius[b];
    const double turning = reach > 0.0 ? momentUnbalanced / (reach * reach) : 0.0;
    totals.largestUnbalancedForce = std::max(totals.largestUnbalancedForce, std::sqrt(unbalanced + turning));
    bl.velocity[b] = v;
    bl.angularVelocity[b] = w;
    if (v.x != 0.0 || v.y != 0.0 || w != 0.0) {
      bl.centroid[b] += dt * v;  // 1.3-15
      bl.rotation[b] += dt * w;
      placeBlockVertices(m, b);
      totals.largestDisplacement =
          std::max(totals.largestDisplacement, (norm(v) + std::abs(w) * bl.boundingRadius[b]) * dt);
    }
  }
  return totals;
}

double rigidBlockTimeStep(const Model& m, double frac) {
  // The smallest block that moves under forces, and l_typ the longest edge of such a block: the
  // stiffness a face puts on a block is kn times the length shared, which no edge of that block
  // exceeds, so a long fixed boundary block does not shorten the step. When every block is
  // driven (a kinematic test), all blocks count, so that driven loading still advances in small
  // increments.
  bool anyFree = false;
  for (int b = 0; b < m.blocks.size(); ++b) anyFree = anyFree || m.blocks.movesFreely(b);
  double minMass = INFINITY, longestEdge = 0.0;
  for (int b = 0; b < m.blocks.size(); ++b) {
    if (anyFree && !m.blocks.movesFreely(b)) continue;
    minMass = std::min(minMass, m.blocks.mass[b]);
    const int first = m.blocks.firstVertex[b], last = first + m.blocks.vertexCount[b];
    for (int v = first; v < last; ++v) longestEdge = std::max(longestEdge, m.vertices.geometry[v].edgeLength);
  }
  double maxStiffness = 0.0;
  for (const JointMaterial& j : m.jointMaterials) {
    const double k = std::max(j.kn, j.ks);
    maxStiffness = std::max(maxStiffness, j.law == JointLaw::PointContact ? k : k * longestEdge);
  }
  if (maxStiffness <= 0.0) throw SceneError("the scene has no joint material: define at least one [[joint_material]]");
  const double dt = frac * 2.0 * std::sqrt(minMass / maxStiffness);  // 1.3-28
  if (!(std::isfinite(dt) && dt > 0.0)) {
    std::ostringstream s;
    s << "the rigid-block time step (1.3-28) from the smallest free block mass " << minMass
      << " kg/m and the largest joint stiffness " << maxStiffness << " N/m (kn or ks times the longest edge, "
      << longestEdge << " m) is " << dt << " s: lower [[joint_material]] kn and ks, or the block density, so that "
      << "both and their ratio are finite";
    throw SceneError(s.str());
  }
  return dt;
}

}  // namespace vdec
