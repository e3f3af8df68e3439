#include "contact/contact_forces.hpp"

#include <algorithm>
#include <limits>
#include <cmath>
#include <sstream>
#include <utility>

#include "contact/contact_geometry.hpp"
#include "contact/strained_outline.hpp"
#include "core/errors.hpp"
#include "core/parallel.hpp"
#include "core/thread_team.hpp"
#include "joint/joint_laws.hpp"

namespace vdec {

namespace {

[[noreturn]] void reportOverlap(const Model& m, const Contact& c, std::size_t index) {
  std::ostringstream s;
  s << "contact " << index << " (corner " << c.corner - m.blocks.firstVertex[c.blockA] << " of block '"
    << m.blocks.name[c.blockA] << "' on block '" << m.blocks.name[c.blockB] << "') overlaps by " << c.overlap
    << " m, more than half the rounding length (" << 0.5 * m.roundingLength << " m) at cycle " << m.cycle
    << ", time " << m.time << " s. The joint is too soft for its load or the step is unstable: raise the "
    << "joint stiffness kn, lower solver.frac, or raise model.rounding.";
  throw OverlapError(s.str());
}

// The edge of A adjacent to corner v whose region (not v's corner region, which wins ties) holds
// the arc centre of B's corner w, or -1. The same regions as followFeature's, without a walk.
int adjacentEdgeHolding(const Model& m, int v, int w) {
  const Vertices& vx = m.vertices;
  const double d = m.roundingLength, tie = 1e-9 * d;
  const Vec2 centre = vx.geometry[w].arcCentre;
  const double sAfter = dot(centre - vx.geometry[v].position, vx.geometry[v].edgeDirection);  // on edge v -> next
  if (sAfter > d + tie && sAfter <= vx.geometry[v].edgeLength - d) return v;
  const int before = vx.prev[v];  // edge prev -> v
  const double sBefore = dot(centre - vx.geometry[before].position, vx.geometry[before].edgeDirection);
  if (sBefore < vx.geometry[before].edgeLength - d - tie && sBefore >= d) return before;
  return -1;
}

// The contact's feature on B for the blocks' new positions. A corner-corner contact whose other
// corner has moved onto the face of A (the two corners slid past each other) becomes that
// corner's contact on A's edge, keeping its state: stresses and displacements are the same
// numbers seen from the other side (normal and tangent both reverse).
FeatureHit trackFeature(const Model& m, Contact& c) {
  const FeatureHit hit = followFeature(m, c.corner, c.blockB, c.feature, c.featureKind);
  if (hit.kind != FeatureKind::Corner) return hit;
  const int edge = adjacentEdgeHolding(m, c.corner, hit.feature);
  if (edge < 0) return hit;
  const int w = hit.feature;
  c.corner = w;
  std::swap(c.blockA, c.blockB);
  return followFeature(m, w, c.blockB, edge, FeatureKind::Edge);
}


Vec2 pointVelocity(const Model& m, const BlockPoint& p) {
  Vec2 v = p.weight[0] * m.gridpoints.velocity[p.gridpoint[0]];
  if (p.gridpoint[1] >= 0) v += p.weight[1] * m.gridpoints.velocity[p.gridpoint[1]];
  return v;
}

void addPointForce(Model& m, const BlockPoint& p, Vec2 f) {
  m.gridpoints.contactForce[p.gridpoint[0]] += p.weight[0] * f;
  if (p.gridpoint[1] >= 0) m.gridpoints.contactForce[p.gridpoint[1]] += p.weight[1] * f;
}

// What a contact's update leaves for the blocks: the force on A from B and its moments.
struct ContactLoad {
  Vec2 force;
  double momentA = 0.0, momentB = 0.0;  // about the centroids, of force on A and of -force on B
  bool applied = false;                 // false for a skipped contact
};

// Where the force acts on deformable outlines and on simply-deformable blocks' strain modes,
// kept only in scenes that have them (the loads of a rigid scene stay small).
struct ContactPoints {
  BlockPoint pa, pb;     // on a deformable outline: its gridpoints
  int ka = -1, kb = -1;  // simply-deformable blocks' strain modes, and where the force acts
  Vec2 Xa, Xb;           // in their body frames
};

// Contact i's update: its geometry, increments, joint law, energies and force. Reads the blocks
// and writes only the contact, its yielding state, `load` and `totals`, so that contacts can be
// updated on several threads. Returns false, leaving the load unapplied, when the contact
// overlaps more than half the rounding length.
bool updateContact(Model& m, std::size_t i, double dt, double motionClock, double beta, ContactStepTotals& totals,
                   ContactLoad& load, ContactPoints* points) {
  Blocks& bl = m.blocks;
  const bool strained = m.strainModes.size() > 0;
  const double overlapLimit = 0.5 * m.roundingLength;
  load.applied = false;
  {
    Contact& c = m.contacts[i];
    if (c.open && motionClock < c.closableAt) {
      c.skipped = true;
      return true;
    }
    const bool caughtUp = c.skipped;
    c.skipped = false;
    const int cornerBefore = c.corner, featureBefore = c.feature;
    const bool cornerToCorner = c.featureKind == FeatureKind::Corner;
    const FeatureHit hit = trackFeature(m, c);
    // Two corners that have slid a rounding length past each other (not two corners of a grid
    // point, where vibration alone moves the contact between corner and edge).
    if (cornerToCorner && hit.kind == FeatureKind::Edge &&
        norm(m.vertices.geometry[cornerBefore].position - m.vertices.geometry[featureBefore].position) > m.roundingLength) {
      totals.passedCorners.push_back(c.blockA);
      totals.passedCorners.push_back(c.blockB);
    }
    const double dun = hit.overlap - c.overlap;  // closing positive
    c.feature = hit.feature;
    c.featureKind = hit.kind;
    c.overlap = hit.overlap;
    if (c.overlap > overlapLimit) return false;

    const int a = c.blockA, b = c.blockB;
    const Vec2 ra = hit.point - bl.centroid[a], rb = hit.point - bl.centroid[b];
    // Velocities are those of the half step just ended, so v dt is this step's increment.
    const bool outlines = bl.deformable[a] || bl.deformable[b];
    const BlockPoint pa = outlines ? cornerPoint(m, c.corner) : BlockPoint{};
    // B is taken at the point facing A's: where a gridpoint of A is, the material point of B
    // across from it (not the rounded tip's, up to d away), so that the relative motion is that
    // of two material points and a uniform strain shared by both sides shears no joint.
    const Vec2 facing = pa.onGridpoints() ? m.vertices.geometry[c.corner].position : hit.point;
    const BlockPoint pb = outlines ? featurePoint(m, hit, facing) : BlockPoint{};
    Vec2 va = pa.onGridpoints() ? pointVelocity(m, pa) : bl.velocity[a] + bl.angularVelocity[a] * perp(ra);
    Vec2 vb = pb.onGridpoints() ? pointVelocity(m, pb) : bl.velocity[b] + bl.angularVelocity[b] * perp(rb);
    // A simply-deformable block's contact point moves with its strain too, and loads its strains.
    StrainModes& modes = m.strainModes;
    const int ka = strained ? modes.of[a] : -1, kb = strained ? modes.of[b] : -1;
    const Vec2 Xa = ka >= 0 ? bodyPoint(modes, ka, ra) : Vec2{}, Xb = kb >= 0 ? bodyPoint(modes, kb, rb) : Vec2{};
    if (ka >= 0) va += strainVelocityAt(modes, ka, Xa);
    if (kb >= 0) vb += strainVelocityAt(modes, kb, Xb);
    const Vec2 tangent{hit.normal.y, -hit.normal.x};
    const double dus = dot(va - vb, tangent) * dt;

    const JointMaterial& j = m.jointMaterials[c.joint];
    const double weightBefore = contactWeight(j, c);
    const double fnBefore = weightBefore * c.normalStress, fsBefore = weightBefore * c.shearStress;
    const double energyBefore = c.springEnergy;
    const bool openBefore = c.open;
    const double slip = j.law == JointLaw::ContinuouslyYielding
                            ? updateContinuouslyYielding(j, c, m.yieldingStates[i], dun, dus)
                            : updateJointStresses(j, c, dun, dus);
    // The length matters only while the contact carries stress.
    if (!c.open) {
      // Between rigid blocks a contact closed over the step keeps its springs' energy across the
      // change of its length; one that has just closed held none, and its length from before it
      // opened is stale. On a deformable outline the length is the gridpoint's share of the joint,
      // which strains with the zones: there the stress is the joint's and is held.
      const double length = contactLength(m, c.corner, hit, outlines);
      if (!openBefore && !outlines) keepSpringEnergyAcrossLength(j, c, c.length / length);
      c.length = length;
    }
    const double weight = contactWeight(j, c);
    const double fn = weight * c.normalStress, fs = weight * c.shearStress;
    totals.slipDissipation += weightBefore * slip;
    // Energy account of the contact over the step: the work of its forces on the displacement
    // increments (trapezoidal) is what its springs stored, what slip dissipated, and the rest,
    // which the joint released without work.
    const double energy = c.open ? 0.0 : weight * jointSpringEnergy(j, c);
    c.springEnergy = energy;
    // A contact evaluated again after steps left out spans all of them in dun; the work of this
    // step is over this step's own approach, taken from the velocities as dus is.
    const double dunStep = caughtUp ? -dot(va - vb, hit.normal) * dt : dun;
    const double work = 0.5 * ((fnBefore + fn) * dunStep + (fsBefore + fs) * dus);
    totals.jointRelease += work - (energy - energyBefore) - weightBefore * slip;
    c.normalDisplacement += dun;
    c.shearDisplacement += dus;
    if (c.open) {
      // Two points of the blocks approach by at most twice the largest vertex displacement, so
      // the joint cannot close (its normal spring reach zero stress) before the clock has moved
      // half the remaining closure on.
      // (An open spring is in its zero-stress stiffness kn for every law.)
      c.closableAt = motionClock + 0.5 * (-c.elasticNormalStress / j.kn);
    }

    // Stiffness-proportional damping (1.3.4.4): a viscous stress on the springs' elastic
    // increments, applied with the force but not stored in the joint's stress; none while the
    // shear spring slips (its increment is then plastic), none while the contact is open.
    double fnViscous = 0.0, fsViscous = 0.0;
    if (beta > 0.0 && !c.open && dt > 0.0) {
      fnViscous = weight * beta * j.kn * dunStep / dt;
      if (slip == 0.0) fsViscous = weight * beta * j.ks * dus / dt;
      totals.viscousDissipation += fnViscous * dunStep + fsViscous * dus;
    }
    // Force on A from B; the shear force resists A's motion along the tangent.
    const Vec2 f = (fn + fnViscous) * hit.normal - (fs + fsViscous) * tangent;
    load.applied = true;
    load.force = f;
    load.momentA = pa.onGridpoints() ? 0.0 : cross(ra, f);
    load.momentB = pb.onGridpoints() ? 0.0 : cross(rb, f);
    if (points) *points = {pa, pb, ka, kb, Xa, Xb};

    if (!c.open) {
      if (j.law == JointLaw::ContinuouslyYielding && (bl.movesFreely(a) || bl.movesFreely(b))) {
        const double stiffness = cyStiffness(j, c);
        if (stiffness > totals.largestGrownStiffness) {
          totals.largestGrownStiffness = stiffness;
          totals.stiffestContact = static_cast<int>(i);
        }
      }
      totals.strainEnergy += energy;
      totals.sumForceMagnitude += std::sqrt(fn * fn + fs * fs);
      ++totals.closedContacts;
    }
  }
  return true;
}

// The load on both blocks: on a rigid or simply-deformable block its force and moment (and the
// strain modes' loads), on a deformable outline its gridpoints' contact forces.
void applyLoad(Model& m, const Contact& c, const ContactLoad& load, const ContactPoints* points) {
  Blocks& bl = m.blocks;
  const Vec2 f = load.force;
  if (points && points->pa.onGridpoints()) {
    addPointForce(m, points->pa, f);
  } else {
    bl.force[c.blockA] += f;
    bl.moment[c.blockA] += load.momentA;
    if (points && points->ka >= 0) addStrainForceAt(m.strainModes, points->ka, points->Xa, f);
  }
  if (points && points->pb.onGridpoints()) {
    addPointForce(m, points->pb, -f);
  } else {
    bl.force[c.blockB] -= f;
    bl.moment[c.blockB] -= load.momentB;
    if (points && points->kb >= 0) addStrainForceAt(m.strainModes, points->kb, points->Xb, -f);
  }
}

}  // namespace

namespace {

struct ContactPartial {
  ContactStepTotals totals;
  int firstOverlap = std::numeric_limits<int>::max();
};

void mergeContactPartial(ContactPartial& total, const ContactPartial& part) {
  ContactStepTotals& t = total.totals;
  const ContactStepTotals& q = part.totals;
  t.strainEnergy += q.strainEnergy;
  t.jointRelease += q.jointRelease;
  t.sumForceMagnitude += q.sumForceMagnitude;
  t.slipDissipation += q.slipDissipation;
  t.viscousDissipation += q.viscousDissipation;
  t.closedContacts += q.closedContacts;
  if (q.largestGrownStiffness > t.largestGrownStiffness) {  // the first contact of the largest
    t.largestGrownStiffness = q.largestGrownStiffness;
    t.stiffestContact = q.stiffestContact;
  }
  t.passedCorners.insert(t.passedCorners.end(), q.passedCorners.begin(), q.passedCorners.end());
  total.firstOverlap = std::min(total.firstOverlap, part.firstOverlap);
}

}  // namespace

ContactStepTotals computeContactForces(Model& m, double dt, double motionClock, double beta) {
  // The contacts go in fixed chunks whose sums are combined in chunk order (core/parallel.hpp),
  // and their loads are applied to the blocks in contact order, so that every sum is formed in
  // the same order at any thread count. On one thread each load is applied as it is formed; on
  // several, the chunks are shared and the loads applied afterwards.
  const int count = static_cast<int>(m.contacts.size());
  const bool withPoints = m.zones.size() > 0 || m.strainModes.size() > 0;
  ContactPartial all;
  if (ThreadTeam::instance().threadCount() == 1) {
    ContactLoad load;
    ContactPoints points;
    ContactPoints* at = withPoints ? &points : nullptr;
    for (int begin = 0; begin < count; begin += kReduceChunk) {
      ContactPartial part;
      for (int i = begin; i < std::min(count, begin + kReduceChunk); ++i) {
        const auto c = static_cast<std::size_t>(i);
        if (!updateContact(m, c, dt, motionClock, beta, part.totals, load, at))
          part.firstOverlap = std::min(part.firstOverlap, i);
        else if (load.applied)
          applyLoad(m, m.contacts[c], load, at);
      }
      mergeContactPartial(all, part);
    }
  } else {
    // Kept from step to step: no allocation while running.
    static thread_local std::vector<ContactLoad> loadBuffer;
    static thread_local std::vector<ContactPoints> pointBuffer;
    std::vector<ContactLoad>& loads = loadBuffer;
    std::vector<ContactPoints>& points = pointBuffer;
    loads.resize(m.contacts.size());
    points.resize(withPoints ? m.contacts.size() : 0);
    all = deterministicReduceChunks<ContactPartial>(count, [&](int begin, int end, ContactPartial& part) {
      for (int i = begin; i < end; ++i) {
        const auto c = static_cast<std::size_t>(i);
        if (!updateContact(m, c, dt, motionClock, beta, part.totals, loads[c], withPoints ? &points[c] : nullptr))
          part.firstOverlap = std::min(part.firstOverlap, i);
      }
    }, mergeContactPartial);
    if (all.firstOverlap == std::numeric_limits<int>::max())
      for (std::size_t i = 0; i < m.contacts.size(); ++i)
        if (loads[i].applied) applyLoad(m, m.contacts[i], loads[i], withPoints ? &points[i] : nullptr);
  }
  if (all.firstOverlap != std::numeric_limits<int>::max())
    reportOverlap(m, m.contacts[static_cast<std::size_t>(all.firstOverlap)], static_cast<std::size_t>(all.firstOverlap));
  return all.totals;
}

}  // namespace vdec
