#pragma once
// The members of Model that a saved state carries (core/state_archive.hpp): all of them, the
// set-up's as well as the run's, so that a restart cannot miss one. Loading overwrites a model
// built from the same scene, whose set-up parts are then already equal.
#include "core/model.hpp"
#include "core/state_archive.hpp"

namespace vdec {

template <class A>
void visitState(A& a, TimeFunction& f) {
  a(f.kind), a(f.start), a(f.rate), a(f.frequency), a(f.phase), a(f.t), a(f.f), a(f.name), a(f.integrated);
  a(f.antiderivative), a(f.atZero);
}
template <class A>
void visitState(A& a, BlockMaterial& m) {
  a(m.name), a(m.density), a(m.bulk), a(m.shear), a(m.plastic), a(m.mohrCoulomb);
}
template <class A>
void visitState(A& a, JointMaterial& j) {
  a(j.name), a(j.law), a(j.kn), a(j.ks), a(j.tanFriction), a(j.cohesion), a(j.tension), a(j.tanDilation);
  a(j.knCoefficient), a(j.knExponent), a(j.ksCoefficient), a(j.ksExponent), a(j.friction), a(j.initialFriction);
  a(j.roughness), a(j.aperture), a(j.residualAperture), a(j.maxAperture), a(j.pointPermeability);
}
template <class A>
void visitState(A& a, FlowBoundary& b) {
  a(b.name), a(b.lo), a(b.hi), a(b.inflow), a(b.value), a(b.waterTable), a(b.history), a(b.timeOrigin), a(b.active);
}
template <class A>
void visitState(A& a, FlowState& f) {
  a(f.present), a(f.on), a(f.fluid), a(f.boundaries), a(f.knots), a(f.sides), a(f.domains), a(f.totals), a(f.subStep);
  a(f.subSteps), a(f.solveIterations), a(f.unbalancedRatio);
}
template <class A>
void visitState(A& a, Blocks& b) {
  a(b.name), a(b.material), a(b.firstVertex), a(b.vertexCount), a(b.mass), a(b.inertia), a(b.driven);
  a(b.boundingRadius), a(b.initialCentroid), a(b.centroid), a(b.rotation), a(b.velocity), a(b.angularVelocity);
  a(b.force), a(b.moment), a(b.appliedForce), a(b.appliedMoment), a(b.deformable), a(b.velocityHistory);
  a(b.inputVelocity), a(b.inputAngularVelocity), a(b.dashpotForce), a(b.dashpotMoment), a(b.boundaryForce);
  a(b.boundaryMoment);
}
template <class A>
void visitState(A& a, Vertices& v) {
  a(v.block), a(v.gridpoint), a(v.pointCorner), a(v.geometry), a(v.localPosition), a(v.localArcCentre);
  a(v.localEdgeDirection), a(v.next), a(v.prev);
}
template <class A>
void visitState(A& a, Gridpoints& g) {
  a(g.block), a(g.initialPosition), a(g.position), a(g.velocity), a(g.tractionForce), a(g.mass), a(g.gravityMass);
  a(g.stiffness), a(g.driven), a(g.contactForce), a(g.dashpotForce);
}
template <class A>
void visitState(A& a, Zones& z) {
  a(z.gridpoint), a(z.block), a(z.material), a(z.sxx), a(z.syy), a(z.sxy), a(z.szz), a(z.plasticState);
  a(z.nodalForce);
}
template <class A>
void visitState(A& a, FreeFieldColumn& c) {
  a(c.nodeY), a(c.nodeMass), a(c.nodeVelocity), a(c.elementMaterial), a(c.sxx), a(c.syy), a(c.sxy);
  a(c.baseNormalImpedance), a(c.baseShearImpedance), a(c.inputVelocity), a(c.history), a(c.timeOrigin);
  a(c.edges), a(c.reactionGridpoint), a(c.reaction), a(c.source);
}
template <class A>
void visitState(A& a, BoundaryCondition& b) {
  a(b.name), a(b.gridpoints), a(b.fix), a(b.velocityBits), a(b.velocity), a(b.history), a(b.edges), a(b.dashpots);
  a(b.rigidDashpots), a(b.freeField), a(b.active);
}
template <class A>
void visitState(A& a, BeamMaterial& b) {
  a(b.name), a(b.young), a(b.area), a(b.inertia), a(b.density), a(b.tieNormalStiffness), a(b.tieShearStiffness);
  a(b.tieCohesion), a(b.tieFriction), a(b.tieTension);
}
template <class A>
void visitState(A& a, Beam& b) {
  a(b.name), a(b.material), a(b.firstNode), a(b.nodeCount), a(b.firstElement), a(b.elementCount), a(b.closed), a(b.tied), a(b.installed);
}
template <class A>
void visitState(A& a, CableMaterial& c) {
  a(c.name), a(c.young), a(c.area), a(c.density), a(c.yieldTension), a(c.yieldCompression), a(c.bondStiffness);
  a(c.bondStrength), a(c.spacing);
}
template <class A>
void visitState(A& a, Cable& c) {
  a(c.name), a(c.material), a(c.direction), a(c.firstNode), a(c.nodeCount), a(c.firstElement), a(c.elementCount);
  a(c.freeLength), a(c.pretension), a(c.head), a(c.installed);
}
template <class A>
void visitState(A& a, BoltMaterial& b) {
  a(b.name), a(b.axialStiffness), a(b.shearStiffness), a(b.axialStrength), a(b.shearStrength), a(b.activeLength);
  a(b.crushing);
}
template <class A>
void visitState(A& a, Bolt& b) {
  a(b.name), a(b.material), a(b.from), a(b.to), a(b.direction), a(b.firstCrossing), a(b.crossingCount), a(b.installed);
}
template <class A>
void visitState(A& a, Structures& s) {
  BeamNodes& n = s.nodes;
  BeamElements& e = s.elements;
  a(s.materials), a(s.beams), a(n.beam), a(n.initialPosition), a(n.position), a(n.rotation), a(n.velocity);
  a(n.angularVelocity), a(n.force), a(n.moment), a(n.tieForce), a(n.forceScale), a(n.appliedForce), a(n.appliedMoment), a(n.mass);
  a(n.rotaryInertia), a(n.length), a(n.fixed), a(e.node), a(e.beam), a(e.restLength), a(e.restAngle);
  a(e.axialForce), a(e.shearForce), a(e.endMoment), a(s.ties);
  CableNodes& cn = s.cableNodes;
  CableElements& ce = s.cableElements;
  a(s.cableMaterials), a(s.cables), a(cn.cable), a(cn.position), a(cn.displacement), a(cn.velocity), a(cn.force);
  a(cn.forceScale), a(cn.appliedForce), a(cn.mass), a(cn.length), a(cn.fixed), a(cn.slip), a(cn.bondForce);
  a(cn.slipping), a(cn.hold), a(ce.node), a(ce.cable), a(ce.restLength), a(ce.axialForce);
  BoltCrossings& x = s.crossings;
  a(s.boltMaterials), a(s.bolts), a(x.bolt), a(x.point), a(x.jointDirection), a(x.side), a(x.displacement);
  a(x.axialDisplacement), a(x.axialForce), a(x.shearForce), a(x.broken);
}
template <class A>
void visitState(A& a, BoundaryElementField& b) {
  a(b.on), a(b.young), a(b.poisson), a(b.halfPlane), a(b.surfaceY), a(b.closed), a(b.node), a(b.firstMember);
  a(b.memberGridpoint), a(b.memberVertex), a(b.memberWeight), a(b.edge), a(b.edgeMember), a(b.inSitu), a(b.inSituGradientX), a(b.inSituGradientY);
  a(b.stiffness), a(b.memberInitialForce), a(b.force), a(b.buildSeconds);
}
template <class A>
void visitState(A& a, HeatField& h) {
  a(h.on), a(h.theta), a(h.step), a(h.stableStep), a(h.time), a(h.steps), a(h.factorisations), a(h.nodeOfGridpoint);
  a(h.temperature), a(h.capacity), a(h.fixed), a(h.fixedValue), a(h.fixedHistory), a(h.histories), a(h.rowStart), a(h.column), a(h.conductance), a(h.decays);
  a(h.loadNode), a(h.loadDecay), a(h.loadHistory), a(h.loadPower), a(h.loadBoundary), a(h.convectionNode), a(h.convectionConductance);
  a(h.convectionAmbient), a(h.radiationNode), a(h.radiationCoefficient), a(h.radiationAmbient), a(h.zoneTemperature), a(h.stored), a(h.sources), a(h.boundary), a(h.fixedInflow);
}
template <class A>
void visitState(A& a, StrainModes& s) {
  a(s.of), a(s.block), a(s.area), a(s.strain), a(s.strainRate), a(s.stress), a(s.szz), a(s.turn), a(s.inverseStretch);
  a(s.force), a(s.massInverse);
  a(s.strainMassInverse), a(s.mass);
}
template <class A>
void visitState(A& a, Model& m) {
  a(m.blockMaterials), a(m.jointMaterials), a(m.blocks), a(m.vertices), a(m.gridpoints), a(m.zones);
  a(m.gridpointZones.start), a(m.gridpointZones.place), a(m.loadedEdges), a(m.drivenVelocities);
  a(m.boundaryConditions), a(m.viscousEdges), a(m.rigidViscousEdges), a(m.freeFields), a(m.initialWaves);
  a(m.timeFunctions), a(m.flow), a(m.structures), a(m.boundaryElements), a(m.heat), a(m.strainModes), a(m.boundaryEdges), a(m.contacts), a(m.yieldingStates), a(m.jointAssignments);
  a(m.defaultJoint), a(m.gravity), a(m.roundingLength), a(m.contactTolerance), a(m.time), a(m.cycle);
}

}  // namespace vdec
