#include "motion/strain_modes.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace vdec {

namespace {

using Matrix4 = Eigen::Matrix4d;
using Vector4 = Eigen::Vector4d;

Polygon localPolygon(const Model& m, int b) {
  Polygon p;
  const int first = m.blocks.firstVertex[b];
  for (int v = first; v < first + m.blocks.vertexCount[b]; ++v) p.push_back(m.vertices.localPosition[v]);
  return p;
}

// The velocity fields of the modes (rotation, e11, e22, e12) at the body point X: their
// columns are the 2 x 4 map from the modes' rates to the point's velocity in the block's frame.
Eigen::Matrix<double, 2, 4> modeFields(Vec2 X) {
  Eigen::Matrix<double, 2, 4> J;
  J << -X.y, X.x, 0.0, X.y,
        X.x, 0.0, X.y, X.x;
  return J;
}

Matrix4 massOf(const StrainModes& s, int k) { return Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(s.mass[k].data()); }

Vector4 modeRates(const Model& m, int b) {
  const Sym2& r = m.strainModes.strainRate[m.strainModes.of[b]];
  return {m.blocks.angularVelocity[b], r.xx, r.yy, r.xy};
}

// The mass of block b's modes (rotation, e11, e22, e12) from its local shape and density.
Matrix4 modeMass(const Model& m, int b) {
  const SecondMoments j = secondMoments(localPolygon(m, b));
  Matrix4 mass;
  mass << j.xx + j.yy, -j.xy, j.xy, j.xx - j.yy,
          -j.xy, j.xx, 0.0, j.xy,
          j.xy, 0.0, j.yy, j.xy,
          j.xx - j.yy, j.xy, j.xy, j.xx + j.yy;
  return m.blockMaterials[m.blocks.material[b]].density * mass;
}

void storeMass(StrainModes& s, int k, const Matrix4& mass) {
  Eigen::Map<Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(s.mass[k].data()) = mass;
  Eigen::Map<Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(s.massInverse[k].data()) = mass.inverse();
  Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(s.strainMassInverse[k].data()) =
      mass.bottomRightCorner<3, 3>().inverse();
}


}  // namespace

void addStrainModes(Model& m, int b) {
  StrainModes& s = m.strainModes;
  if (s.of.size() < static_cast<std::size_t>(m.blocks.size())) s.of.resize(m.blocks.size(), -1);
  const int k = s.size();
  s.of[b] = k;
  s.block.push_back(b);
  s.area.push_back(signedArea(localPolygon(m, b)));
  s.strain.push_back({});
  s.strainRate.push_back({});
  s.stress.push_back({});
  s.szz.push_back(0.0);
  s.turn.push_back({1.0, 0.0});
  s.inverseStretch.push_back({1.0, 1.0, 0.0});
  s.force.push_back({});
  s.mass.emplace_back();
  s.massInverse.emplace_back();
  s.strainMassInverse.emplace_back();
  storeMass(s, k, modeMass(m, b));
}

Sym2 presentStress(const Model& m, int b, double& szz) {
  const BlockMaterial& mat = m.blockMaterials[m.blocks.material[b]];
  const double lambda = mat.bulk - 2.0 * mat.shear / 3.0, g = mat.shear;
  const Sym2& e = m.strainModes.strain[m.strainModes.of[b]];
  szz = lambda * (e.xx + e.yy);
  return {(lambda + 2.0 * g) * e.xx + lambda * e.yy, lambda * e.xx + (lambda + 2.0 * g) * e.yy, 2.0 * g * e.xy};
}

double strainModeStress(Model& m) {
  StrainModes& s = m.strainModes;
  double energy = 0.0;
  for (int k = 0; k < s.size(); ++k) {
    const Sym2& e = s.strain[k];
    const Sym2& sigma = s.stress[k] = presentStress(m, s.block[k], s.szz[k]);
    energy += 0.5 * s.area[k] * (sigma.xx * e.xx + sigma.yy * e.yy + 2.0 * sigma.xy * e.xy);
  }
  return energy;
}

void advanceStrainModes(Model& m, int b, double dt, double alpha, double local, double bodyMoment,
                        double translationUnbalanced, MotionStepTotals& totals) {
  Blocks& bl = m.blocks;
  StrainModes& s = m.strainModes;
  const int k = s.of[b];
  const bool rotationDriven = (bl.driven[b] & DriveRotation) != 0;
  const Sym2& q = s.force[k];
  const Sym2& sigma = s.stress[k];
  const double area = s.area[k];
  // The generalised loads: the moment, and the strain forces of the contacts less the elastic
  // ones, dU/dE = A (sigma_xx, sigma_yy, 2 sigma_xy).
  const Vector4 load{bl.moment[b] + bodyMoment, q.xx - area * sigma.xx, q.yy - area * sigma.yy,
                     q.xy - 2.0 * area * sigma.xy};
  const Sym2& rate = s.strainRate[k];
  const Vector4 v0{bl.angularVelocity[b], rate.xx, rate.yy, rate.xy};
  Vector4 damping = Vector4::Zero();
  for (int i = rotationDriven ? 1 : 0; i < 4; ++i) damping[i] = localDampingForce(local, load[i], v0[i]);
  const double lose = 1.0 - 0.5 * alpha * dt, keep = 1.0 / (1.0 + 0.5 * alpha * dt);
  Vector4 v1 = v0;
  if (rotationDriven) {
    // The driver holds the rotation at its velocity and does work through the moment it takes.
    totals.externalWork -= bl.moment[b] * v0[0] * dt;
    const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> inverse(s.strainMassInverse[k].data());
    v1.tail<3>() = keep * (lose * v0.tail<3>() + dt * (inverse * (load + damping).tail<3>()));
  } else {
    const Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>> inverse(s.massInverse[k].data());
    v1 = keep * (lose * v0 + dt * (inverse * (load + damping)));
  }
  // The energy sums of the free modes, as integrateRigidBlocks forms them for one degree of
  // freedom, with the mass matrix in place of the mass.
  Matrix4 mass = massOf(s, k);
  if (rotationDriven) mass.row(0).setZero(), mass.col(0).setZero();
  const Vector4 vbar = 0.5 * (v0 + v1), momentum0 = mass * v0, momentum1 = mass * v1;
  const double power = 0.5 * vbar.dot(momentum0 + momentum1);  // vbar^T M vbar
  totals.kineticEnergy += 0.25 * (v0.dot(momentum0) + v1.dot(momentum1));
  totals.kineticLag += 0.5 * v0.dot(momentum1);
  totals.dampingDissipation += alpha * power * dt - damping.dot(vbar) * dt;
  totals.dampingPower += power;
  totals.kineticRate += vbar.dot(momentum1 - momentum0) / dt;
  if (!rotationDriven) totals.externalWork += bodyMoment * v1[0] * dt;
  // Generalised forces as forces at the block's reach, as the rigid moment is counted, in one
  // norm with the translation's.
  const double reach = bl.boundingRadius[b];
  double generalised = 0.0;
  for (int i = rotationDriven ? 1 : 0; i < 4; ++i) generalised += load[i] * load[i];
  totals.largestUnbalancedForce = std::max(
      totals.largestUnbalancedForce, std::sqrt(translationUnbalanced + (reach > 0.0 ? generalised / (reach * reach) : 0.0)));
  bl.angularVelocity[b] = v1[0];
  s.strainRate[k] = {v1[1], v1[2], v1[3]};
  Sym2& e = s.strain[k];
  e.xx += dt * v1[1];
  e.yy += dt * v1[2];
  e.xy += dt * v1[3];
  bl.rotation[b] += dt * v1[0];
}

Sym2 inWorldAxes(const Model& m, int b, const Sym2& t) {
  const double c = std::cos(m.blocks.rotation[b]), s = std::sin(m.blocks.rotation[b]);
  return {c * c * t.xx - 2.0 * c * s * t.xy + s * s * t.yy, s * s * t.xx + 2.0 * c * s * t.xy + c * c * t.yy,
          c * s * (t.xx - t.yy) + (c * c - s * s) * t.xy};
}


double strainModeKineticEnergy(const Model& m, int b) {
  const Vector4 v = modeRates(m, b);
  const Matrix4 mass = massOf(m.strainModes, m.strainModes.of[b]);
  return 0.5 * v.dot(mass * v) - 0.5 * mass(0, 0) * v[0] * v[0];
}

double rotationKineticEnergy(const Model& m, int b) {
  const Vector4 v = modeRates(m, b);
  const Matrix4 mass = massOf(m.strainModes, m.strainModes.of[b]);
  return 0.5 * mass(0, 0) * v[0] * v[0] + v[0] * mass.row(0).tail<3>().dot(v.tail<3>());
}

double stopStrainRates(Model& m, int b) {
  StrainModes& s = m.strainModes;
  const Vector4 v = modeRates(m, b);
  const Matrix4 mass = massOf(s, s.of[b]);
  // What the kinetic energy loses when the strain rates (v[1..3]) go and omega stays.
  const double energy = 0.5 * v.tail<3>().dot(mass.bottomRightCorner<3, 3>() * v.tail<3>()) +
                        v[0] * mass.row(0).tail<3>().dot(v.tail<3>());
  s.strainRate[s.of[b]] = {};
  return energy;
}

double releaseStrainModes(Model& m, int b) {
  StrainModes& s = m.strainModes;
  const int k = s.of[b];
  const Sym2& e = s.strain[k];
  double szz = 0.0;
  const Sym2 sigma = presentStress(m, b, szz);
  const double elastic = 0.5 * s.area[k] * (sigma.xx * e.xx + sigma.yy * e.yy + 2.0 * sigma.xy * e.xy);
  const double energy = elastic + strainModeKineticEnergy(m, b);
  s.strain[k] = s.strainRate[k] = s.stress[k] = {};
  s.szz[k] = 0.0;
  return energy;
}

void turnStrainFrame(Model& m, int b) {
  StrainModes& s = m.strainModes;
  const int k = s.of[b];
  s.strain[k] = inWorldAxes(m, b, s.strain[k]);
  s.strainRate[k] = inWorldAxes(m, b, s.strainRate[k]);
  s.stress[k] = inWorldAxes(m, b, s.stress[k]);
  storeMass(s, k, modeMass(m, b));
}

double strainModeTimeStep(const Model& m, double frac) {
  const StrainModes& s = m.strainModes;
  double fastest = 0.0;
  for (int k = 0; k < s.size(); ++k) {
    const int b = s.block[k];
    const BlockMaterial& mat = m.blockMaterials[m.blocks.material[b]];
    const double lambda = mat.bulk - 2.0 * mat.shear / 3.0, g = mat.shear;
    Matrix4 stiffness = Matrix4::Zero();
    stiffness.bottomRightCorner<3, 3>() << lambda + 2.0 * g, lambda, 0.0,
                                           lambda, lambda + 2.0 * g, 0.0,
                                           0.0, 0.0, 4.0 * g;
    stiffness *= s.area[k];
    const int first = m.blocks.firstVertex[b], last = first + m.blocks.vertexCount[b];
    double longestEdge = 0.0;
    for (int v = first; v < last; ++v) longestEdge = std::max(longestEdge, norm(m.vertices.localPosition[m.vertices.next[v]] - m.vertices.localPosition[v]));
    double spring = 0.0;
    for (const JointMaterial& j : m.jointMaterials)
      spring = std::max(spring, std::max(j.kn, j.ks) * (j.law == JointLaw::PointContact ? 1.0 : longestEdge));
    for (int v = first; v < last; ++v) {
      const Eigen::Matrix<double, 2, 4> J = modeFields(m.vertices.localPosition[v]);
      stiffness += spring * J.transpose() * J;
    }
    Matrix4 mass = massOf(s, k);
    if (m.blocks.driven[b] & DriveRotation) {
      mass.row(0).setZero(), mass.col(0).setZero(), stiffness.row(0).setZero(), stiffness.col(0).setZero();
      mass(0, 0) = stiffness(0, 0) = 1.0;  // a neutral mode, frequency 1 rad/s
    }
    Eigen::GeneralizedSelfAdjointEigenSolver<Matrix4> modes(stiffness, mass, Eigen::EigenvaluesOnly);
    fastest = std::max(fastest, modes.eigenvalues().maxCoeff());
  }
  return fastest > 0.0 ? frac * 2.0 / std::sqrt(fastest) : INFINITY;
}

}  // namespace vdec
