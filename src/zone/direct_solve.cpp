#include "zone/direct_solve.hpp"

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <chrono>
#include <cmath>
#include <sstream>
#include <vector>

#include "bem/far_field.hpp"
#include "contact/contact_geometry.hpp"
#include "contact/deformable_outline.hpp"
#include "core/errors.hpp"
#include "joint/joint_laws.hpp"
#include "motion/gridpoint_motion.hpp"
#include "zone/cst.hpp"
#include "zone/mohr_coulomb.hpp"

namespace vdec {

namespace {

// Gradients of the linear shape functions of a zone on positions p (b = dN/dx, c = dN/dy).
struct ShapeGradients {
  double b[3], c[3], area;
};

ShapeGradients gradients(Vec2 p0, Vec2 p1, Vec2 p2) {
  const double twice = cross(p1 - p0, p2 - p0);
  const double inv = 1.0 / twice;
  return {{(p1.y - p2.y) * inv, (p2.y - p0.y) * inv, (p0.y - p1.y) * inv},
          {(p2.x - p1.x) * inv, (p0.x - p2.x) * inv, (p1.x - p0.x) * inv},
          0.5 * twice};
}

// A closed joint between deformable blocks as a linear spring: the gridpoints it joins, each
// with its coefficient in the relative displacement u_A - u_B at the contact (1 for A's
// gridpoint, minus B's interpolation weights), and the stiffness W (kn n n^T + ks t t^T).
struct JointSpring {
  int contact = -1;
  int gridpoint[3] = {-1, -1, -1};
  double coefficient[3] = {0.0, 0.0, 0.0};
  Vec2 normal, tangent;
  double kn = 0.0, ks = 0.0;  // times the contact's weight (its length)
};

std::vector<JointSpring> jointSprings(const Model& m) {
  std::vector<JointSpring> springs;
  for (std::size_t i = 0; i < m.contacts.size(); ++i) {
    const Contact& c = m.contacts[i];
    if (c.open) continue;
    const JointMaterial& j = m.jointMaterials[c.joint];
    const FeatureHit hit = contactGeometry(m, c);
    const BlockPoint a = cornerPoint(m, c.corner);
    const BlockPoint b = featurePoint(m, hit, m.vertices.geometry[c.corner].position);
    JointSpring s;
    s.contact = static_cast<int>(i);
    s.gridpoint[0] = a.gridpoint[0];
    s.coefficient[0] = 1.0;
    for (int k = 0; k < 2; ++k) {
      s.gridpoint[1 + k] = b.gridpoint[k];
      s.coefficient[1 + k] = -b.weight[k];
    }
    s.normal = hit.normal;
    s.tangent = {hit.normal.y, -hit.normal.x};
    const double weight = contactWeight(j, c);
    s.kn = weight * j.kn;
    s.ks = weight * j.ks;
    springs.push_back(s);
  }
  return springs;
}

constexpr int kMaxSolves = 6;
constexpr double kResidualTolerance = 1e-12;

// The factorised stiffness of an earlier solve. The later solves correct what the configuration
// reached leaves unbalanced, a residual of the order of the strains times the loads; the first
// solve's stiffness differs from theirs by as little, so solving with its factor converges as
// fast, and a factorisation, the solve's costliest part, is made once. It is made again when the
// joints that carry springs change (one opened or closed in a solve).
struct StiffnessFactor {
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
  Eigen::SparseMatrix<double> stiffness;  // of the present configuration, kept with plastic zones
  std::vector<int> springContacts;
  int unknowns = -1;
};

bool anyPlasticZone(const Model& m) {
  for (int z = 0; z < m.zones.size(); ++z)
    if (m.blockMaterials[m.zones.material[z]].plastic) return true;
  return false;
}

struct ZoneStress {
  double sxx, syy, sxy, szz;
  std::uint8_t state;
};

// The zones as the solve sees them: shape gradients on the configuration of the pass, the
// stresses the pass started from and the elastic constants. stressAt gives a zone's stress after
// the displacement u of the pass, the elastic increment D e(u) returned to the yield surface of a
// Mohr-Coulomb zone in one step from the pass's start (the fully implicit, backward Euler, return
// over the pass's increment: the same mohrCoulombReturn as the explicit cycles').
struct PlasticZones {
  std::vector<ShapeGradients> shape;
  std::vector<std::array<int, 6>> dof;
  const Model* model = nullptr;

  // The elastic trial: the pass's starting stress plus D B u.
  ZoneStress trialAt(int z, const Eigen::VectorXd& u) const {
    const Zones& zn = model->zones;
    const ShapeGradients& s = shape[z];
    double e[3] = {};
    for (int c = 0; c < 3; ++c) {
      const int ix = dof[z][2 * c], iy = dof[z][2 * c + 1];
      const double ux = ix >= 0 ? u[ix] : 0.0, uy = iy >= 0 ? u[iy] : 0.0;
      e[0] += s.b[c] * ux;
      e[1] += s.c[c] * uy;
      e[2] += s.c[c] * ux + s.b[c] * uy;
    }
    const BlockMaterial& mat = model->blockMaterials[zn.material[z]];
    const double a1 = mat.bulk + 4.0 * mat.shear / 3.0, a2 = mat.bulk - 2.0 * mat.shear / 3.0;
    return {zn.sxx[z] + a1 * e[0] + a2 * e[1], zn.syy[z] + a2 * e[0] + a1 * e[1], zn.sxy[z] + mat.shear * e[2],
            zn.szz[z] + a2 * (e[0] + e[1]), Elastic};
  }

  // The trial returned to the yield surface of a plastic zone.
  static ZoneStress returned(const BlockMaterial& mat, ZoneStress t) {
    if (!mat.plastic) return t;
    const double a1 = mat.bulk + 4.0 * mat.shear / 3.0, a2 = mat.bulk - 2.0 * mat.shear / 3.0;
    t.state = mohrCoulombReturn(mat.mohrCoulomb, a1, a2, t.sxx, t.syy, t.sxy, t.szz);
    return t;
  }

  ZoneStress stressAt(int z, const Eigen::VectorXd& u) const {
    return returned(model->blockMaterials[model->zones.material[z]], trialAt(z, u));
  }

  // The forces the returns take off the elastic trial, sum over yielding zones of A B^T (trial -
  // returned): the residual is f - K u + relief(u).
  Eigen::VectorXd relief(const Eigen::VectorXd& u) const {
    const Zones& zn = model->zones;
    Eigen::VectorXd r = Eigen::VectorXd::Zero(u.size());
    for (int z = 0; z < zn.size(); ++z) {
      const BlockMaterial& mat = model->blockMaterials[zn.material[z]];
      if (!mat.plastic) continue;
      const ZoneStress trial = trialAt(z, u);
      const ZoneStress back = returned(mat, trial);
      if (back.state == Elastic) continue;
      const double dxx = trial.sxx - back.sxx, dyy = trial.syy - back.syy, dxy = trial.sxy - back.sxy;
      const ShapeGradients& s = shape[z];
      for (int c = 0; c < 3; ++c) {
        if (dof[z][2 * c] >= 0) r[dof[z][2 * c]] += s.area * (s.b[c] * dxx + s.c[c] * dxy);
        if (dof[z][2 * c + 1] >= 0) r[dof[z][2 * c + 1]] += s.area * (s.c[c] * dyy + s.b[c] * dxy);
      }
    }
    return r;
  }
};

PlasticZones plasticZones(const Model& m, const std::vector<int>& unknown) {
  const Gridpoints& g = m.gridpoints;
  const Zones& zn = m.zones;
  PlasticZones p;
  p.model = &m;
  p.shape.reserve(zn.size());
  p.dof.resize(zn.size());
  for (int z = 0; z < zn.size(); ++z) {
    const auto& n = zn.gridpoint[z];
    p.shape.push_back(gradients(g.position[n[0]], g.position[n[1]], g.position[n[2]]));
    for (int c = 0; c < 3; ++c) {
      p.dof[z][2 * c] = unknown[2 * n[c]];
      p.dof[z][2 * c + 1] = unknown[2 * n[c] + 1];
    }
  }
  return p;
}

constexpr int kAndersonDepth = 8;
constexpr int kMaxPlasticIterations = 2000;
// Iterations without halving the best residual after which the zones are taken to have no
// equilibrium in reach (a load at or beyond collapse): MC-TUNNEL-CONVERGENCE's passes converge in
// 10 to 40.
constexpr int kStagnantIterations = 200;

// Solves f - K u + relief(u) = 0 on one configuration: the fixed point of u -> u + K0^-1 r(u),
// the elastic (initial) stiffness K0 factorised once standing in for the tangent (Zienkiewicz,
// Valliappan and King 1969), accelerated by Anderson mixing of the last iterates (Walker and Ni
// 2011): each step takes the combination of the recent steps that best cancels the latest
// correction, as a secant method would. The returns are exact at every iterate, so the answer is
// the equilibrium of the same stress update the explicit cycles make; only the route differs.
// Without convergence it returns a zero displacement (the pass changes nothing: an iterate far
// from equilibrium is no state to start the cycles from) and clears report.plasticConverged.
Eigen::VectorXd plasticIteration(const PlasticZones& zones, const StiffnessFactor& factor, const Eigen::VectorXd& f,
                                 double target, DirectSolveReport& report) {
  const Eigen::SparseMatrix<double>& K = factor.stiffness;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(f.size());
  std::vector<Eigen::VectorXd> steps, corrections;  // differences of successive G(u) and of F(u)
  Eigen::VectorXd lastG, lastF;
  double lastSize = INFINITY, bestSize = INFINITY;
  int bestIteration = 0;
  for (int iteration = 0, k = 0; iteration < kMaxPlasticIterations; ++iteration, ++k) {
    const Eigen::VectorXd residual = f - K * u + zones.relief(u);
    report.plasticIterations++;
    const double size = residual.norm();
    report.plasticResidual = size;
    if (!(size > target)) return u;
    if (size < 0.5 * bestSize) {
      bestSize = size;
      bestIteration = iteration;
    } else if (iteration - bestIteration > kStagnantIterations || !std::isfinite(size)) {
      break;
    }
    // Mixing across a change of the set of yielding zones (a kink of the map) can mislead; a
    // residual that grows is taken as that sign, and the mixing starts afresh from this iterate.
    if (size > 2.0 * lastSize) {
      steps.clear();
      corrections.clear();
      k = 0;
    }
    lastSize = size;
    const Eigen::VectorXd F = factor.ldlt.solve(residual);  // the fixed-point correction
    const Eigen::VectorXd G = u + F;
    if (k > 0) {
      steps.push_back(G - lastG);
      corrections.push_back(F - lastF);
      if (static_cast<int>(steps.size()) > kAndersonDepth) {
        steps.erase(steps.begin());
        corrections.erase(corrections.begin());
      }
    }
    lastG = G;
    lastF = F;
    u = G;
    const int depth = static_cast<int>(corrections.size());
    if (depth == 0) continue;
    // gamma minimises |F - sum gamma_j dF_j|; plain loops keep the sums' order fixed.
    Eigen::MatrixXd normal(depth, depth);
    Eigen::VectorXd rhs(depth);
    for (int i = 0; i < depth; ++i) {
      rhs[i] = corrections[i].dot(F);
      for (int j = 0; j <= i; ++j) normal(i, j) = normal(j, i) = corrections[i].dot(corrections[j]);
    }
    const Eigen::VectorXd gamma = normal.completeOrthogonalDecomposition().solve(rhs);
    for (int j = 0; j < depth; ++j) u -= gamma[j] * steps[j];
  }
  report.plasticConverged = false;
  return Eigen::VectorXd::Zero(f.size());
}

// One linear solve on the current configuration; returns the norm of the residual it solved for
// and the scale of the forces (loads or zone forces), and adds the largest displacement to
// `report`.
std::pair<double, double> solveOnce(Model& m, DirectSolveReport& report, StiffnessFactor& factor) {
  Gridpoints& g = m.gridpoints;
  Zones& zn = m.zones;
  // Unknowns: the free components; driven ones must be held still.
  std::vector<int> unknown(2 * g.size(), -1);
  int count = 0;
  for (int i = 0; i < g.size(); ++i) {
    for (int d = 0; d < 2; ++d) {
      const bool driven = g.driven[i] & (d == 0 ? DriveX : DriveY);
      const double v = d == 0 ? g.velocity[i].x : g.velocity[i].y;
      if (driven && v != 0.0)
        throw SceneError("solver.static_solve: a gridpoint of block '" + m.blocks.name[g.block[i]] +
                         "' is driven at a velocity; a static solve needs gridpoints fixed or free");
      if (!driven) unknown[2 * i + d] = count++;
    }
  }
  // Loads: gravity and boundary tractions, plus the forces of the zones' present stresses.
  m.clearStepForces();
  applyEdgeTractions(m);
  if (m.boundaryElements.on) applyBoundaryElementForces(m);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(count);
  for (int i = 0; i < g.size(); ++i) {
    const Vec2 load = g.gravityMass[i] * m.gravity + g.tractionForce[i];
    if (unknown[2 * i] >= 0) f[unknown[2 * i]] += load.x;
    if (unknown[2 * i + 1] >= 0) f[unknown[2 * i + 1]] += load.y;
  }
  const Eigen::VectorXd external = f;
  // Joints between the blocks: springs on the relative displacement at each closed contact.
  const std::vector<JointSpring> springs = jointSprings(m);
  std::vector<int> springContacts;
  for (const JointSpring& js : springs) springContacts.push_back(js.contact);
  const bool refactor = factor.unknowns != count || factor.springContacts != springContacts;
  // With plastic zones the elastic stiffness of this configuration forms the residual of the
  // iteration below, so it is assembled on every pass; the factor stays that of an earlier one.
  const bool plastic = anyPlasticZone(m);
  const bool assemble = refactor || plastic;
  std::vector<Eigen::Triplet<double>> entries;
  if (assemble) entries.reserve(36 * static_cast<std::size_t>(zn.size()));
  for (int z = 0; z < zn.size(); ++z) {
    const auto& n = zn.gridpoint[z];
    const ShapeGradients s = gradients(g.position[n[0]], g.position[n[1]], g.position[n[2]]);
    const BlockMaterial& mat = m.blockMaterials[zn.material[z]];
    const double a1 = mat.bulk + 4.0 * mat.shear / 3.0, a2 = mat.bulk - 2.0 * mat.shear / 3.0, G = mat.shear;
    // B (3 x 6): strains (exx, eyy, gxy) from (ux0, uy0, ux1, uy1, ux2, uy2).
    double B[3][6] = {};
    for (int c = 0; c < 3; ++c) {
      B[0][2 * c] = s.b[c];
      B[1][2 * c + 1] = s.c[c];
      B[2][2 * c] = s.c[c];
      B[2][2 * c + 1] = s.b[c];
    }
    const double D[3][3] = {{a1, a2, 0.0}, {a2, a1, 0.0}, {0.0, 0.0, G}};
    double DB[3][6] = {};
    for (int r = 0; r < 3; ++r)
      for (int k = 0; k < 6; ++k)
        for (int q = 0; q < 3; ++q) DB[r][k] += D[r][q] * B[q][k];
    int dof[6];
    for (int c = 0; c < 3; ++c) {
      dof[2 * c] = unknown[2 * n[c]];
      dof[2 * c + 1] = unknown[2 * n[c] + 1];
    }
    // Internal force of the present stress, -A B^T sigma (tension positive), joins the loads.
    const double sigma[3] = {zn.sxx[z], zn.syy[z], zn.sxy[z]};
    for (int k = 0; k < 6; ++k) {
      if (dof[k] < 0) continue;
      double fk = 0.0;
      for (int q = 0; q < 3; ++q) fk -= s.area * B[q][k] * sigma[q];
      f[dof[k]] += fk;
      for (int l = 0; assemble && l < 6; ++l) {
        if (dof[l] < 0) continue;
        double kkl = 0.0;
        for (int q = 0; q < 3; ++q) kkl += B[q][k] * DB[q][l];
        entries.emplace_back(dof[k], dof[l], s.area * kkl);
      }
    }
  }
  // The joints' springs, and the force of their present stresses (on A, f = fn n - fs t; on B its
  // opposite, shared).
  for (const JointSpring& js : springs) {
    const Contact& c = m.contacts[js.contact];
    const double w = contactWeight(m.jointMaterials[c.joint], c);
    const Vec2 force = (w * c.normalStress) * js.normal - (w * c.shearStress) * js.tangent;
    const double S[2][2] = {{js.kn * js.normal.x * js.normal.x + js.ks * js.tangent.x * js.tangent.x,
                             js.kn * js.normal.x * js.normal.y + js.ks * js.tangent.x * js.tangent.y},
                            {js.kn * js.normal.y * js.normal.x + js.ks * js.tangent.y * js.tangent.x,
                             js.kn * js.normal.y * js.normal.y + js.ks * js.tangent.y * js.tangent.y}};
    for (int p = 0; p < 3; ++p) {
      if (js.gridpoint[p] < 0) continue;
      for (int r = 0; r < 2; ++r) {
        const int row = unknown[2 * js.gridpoint[p] + r];
        if (row < 0) continue;
        f[row] += js.coefficient[p] * (r == 0 ? force.x : force.y);
        for (int q = 0; assemble && q < 3; ++q) {
          if (js.gridpoint[q] < 0) continue;
          for (int t = 0; t < 2; ++t) {
            const int col = unknown[2 * js.gridpoint[q] + t];
            if (col >= 0) entries.emplace_back(row, col, js.coefficient[p] * js.coefficient[q] * S[r][t]);
          }
        }
      }
    }
  }
  // The far field's stiffness on its nodes, each node's displacement the weighted mean of its
  // gridpoints' (the solve refuses rigid blocks, so every point of the interface is a gridpoint).
  const BoundaryElementField& be = m.boundaryElements;
  for (int i = 0; assemble && be.on && i < be.size(); ++i)
    for (int j = 0; j < be.size(); ++j)
      for (int p = be.firstMember[i]; p < be.firstMember[i + 1]; ++p)
        for (int q = be.firstMember[j]; q < be.firstMember[j + 1]; ++q) {
          const double share = be.memberWeight[p] * be.memberWeight[q];
          for (int r = 0; r < 2; ++r)
            for (int t = 0; t < 2; ++t) {
              const int row = unknown[2 * be.memberGridpoint[p] + r], col = unknown[2 * be.memberGridpoint[q] + t];
              if (row >= 0 && col >= 0)
                entries.emplace_back(row, col, share * be.stiffness[static_cast<std::size_t>(2 * i + r) * (2 * be.size()) + 2 * j + t]);
            }
        }
  if (plastic) {
    factor.stiffness.resize(count, count);
    factor.stiffness.setFromTriplets(entries.begin(), entries.end());
  }
  if (refactor) {
    Eigen::SparseMatrix<double> K(count, count);
    K.setFromTriplets(entries.begin(), entries.end());
    factor.ldlt.compute(K);
    bool held = factor.ldlt.info() == Eigen::Success;
    if (held) {
      // A stiffness with rigid-body modes factors with (near) zero pivots: reject those.
      const Eigen::VectorXd pivots = factor.ldlt.vectorD();
      const double largest = pivots.cwiseAbs().maxCoeff();
      held = pivots.minCoeff() > 1e-12 * largest;
    }
    if (!held)
      throw SceneError("solver.static_solve: the zones are not held against rigid-body motion (the stiffness "
                       "is singular); fix more gridpoint components, or check that every block is held or joined "
                       "to one that is by closed joints");
    factor.unknowns = count;
    factor.springContacts = std::move(springContacts);
    ++report.factorisations;
  }
  report.unknowns = count;
  const PlasticZones zones = plasticZones(m, unknown);
  Eigen::VectorXd u;
  if (plastic) {
    const double scale = std::max(external.norm(), (f - external).norm());
    u = plasticIteration(zones, factor, f, kResidualTolerance * scale, report);
  } else {
    u = factor.ldlt.solve(f);
  }
  // Apply: stresses take the increment of du on the configuration it was solved on, returned to
  // the yield surface where the zone is plastic.
  for (int z = 0; z < zn.size(); ++z) {
    ZoneStress stress = zones.stressAt(z, u);
    zn.sxx[z] = stress.sxx;
    zn.syy[z] = stress.syy;
    zn.sxy[z] = stress.sxy;
    zn.szz[z] = stress.szz;
    if (stress.state != Elastic || zn.plasticState[z] != Elastic)
      zn.plasticState[z] = static_cast<std::uint8_t>(stress.state | (zn.plasticState[z] != Elastic ? PlasticInPast : 0));
  }
  auto displacement = [&](int i) {
    const int ix = unknown[2 * i], iy = unknown[2 * i + 1];
    return Vec2{ix >= 0 ? u[ix] : 0.0, iy >= 0 ? u[iy] : 0.0};
  };
  // Joints take the increments of their relative displacement through their law, as the contact
  // stage would (closing positive along n, shear along t).
  for (const JointSpring& js : springs) {
    Vec2 relative;
    for (int p = 0; p < 3; ++p)
      if (js.gridpoint[p] >= 0) relative += js.coefficient[p] * displacement(js.gridpoint[p]);
    Contact& c = m.contacts[js.contact];
    const double dun = -dot(relative, js.normal), dus = dot(relative, js.tangent);
    updateJointStresses(m.jointMaterials[c.joint], c, dun, dus);
    c.normalDisplacement += dun;
    c.shearDisplacement += dus;
  }
  for (int i = 0; i < g.size(); ++i) {
    const Vec2 du = displacement(i);
    g.position[i] += du;
    g.velocity[i] = {};
    report.largestDisplacement = std::max(report.largestDisplacement, norm(du));
  }
  // The contacts' geometry at the new positions. A joint that took its increments above has its
  // overlap formed again, so that the first explicit step measures its own closure from here,
  // and its springs' energy counts as given. An open contact keeps the overlap it had: the
  // first explicit step then sees in it what the solve moved the blocks, closing or opening it
  // as the contact stage would, and is evaluated at once (the motion clock has not run).
  if (!g.contactForce.empty()) {
    for (int b = 0; b < m.blocks.size(); ++b)
      if (m.blocks.deformable[b]) placeOutlineVertices(m, b);
    std::vector<char> sprung(m.contacts.size(), 0);
    for (const JointSpring& js : springs) sprung[js.contact] = 1;
    for (std::size_t i = 0; i < m.contacts.size(); ++i) {
      Contact& c = m.contacts[i];
      if (!sprung[i]) {
        // The solve held this joint open (no spring); if the blocks now overlap there, its
        // answer is not one the joint allows.
        if (contactGeometry(m, c).overlap > 0.0) {
          std::ostringstream msg;
          msg << "solver.static_solve: the direct solve closed an open joint (contact " << i << " between blocks '"
              << m.blocks.name[c.blockA] << "' and '" << m.blocks.name[c.blockB] << "'): it takes the joints open or "
              << "closed as they are at the start; close the gap in the scene, or relax it with explicit cycles instead";
          throw SceneError(msg.str());
        }
        c.closableAt = 0.0;
        continue;
      }
      const JointMaterial& j = m.jointMaterials[c.joint];
      const FeatureHit hit = contactGeometry(m, c);
      c.overlap = hit.overlap;
      if (!c.open) c.length = contactLength(m, c.corner, hit, true);
      c.springEnergy = c.open ? 0.0 : contactWeight(j, c) * jointSpringEnergy(j, c);
    }
  }
  // The scale of the forces in play: the loads, or the zones' own forces when in-situ stress
  // alone drives the problem.
  return {f.norm(), std::max(external.norm(), (f - external).norm())};
}

}  // namespace

DirectSolveReport solveStaticDirect(Model& m) {
  const auto start = std::chrono::steady_clock::now();
  DirectSolveReport report;
  // The explicit cycles move the gridpoints and apply the tractions on the deformed outline; the
  // linear solve does not. Solving again on the configuration reached removes that remainder
  // (the stiffness lacks only the geometric terms, so each solve gains about as many digits as
  // the strains are small) until the residual is at round-off of the loads.
  StiffnessFactor factor;
  for (int k = 0; k < kMaxSolves; ++k) {
    ++report.solves;
    const auto [residual, scale] = solveOnce(m, report, factor);
    report.relativeResidual = scale > 0.0 ? residual / scale : 0.0;
    // Plastic zones with no equilibrium in reach (a load near collapse): further passes would
    // not find one either; the explicit cycles take over from here.
    if (!report.plasticConverged) {
      report.relativeResidual = scale > 0.0 ? report.plasticResidual / scale : 0.0;
      break;
    }
    if (!(residual > kResidualTolerance * scale)) break;
  }
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

}  // namespace vdec
