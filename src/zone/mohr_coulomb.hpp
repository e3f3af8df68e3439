#pragma once
// Elastic, perfectly plastic Mohr-Coulomb law for zones with non-associated flow and a tension
// cut-off (NUREG/CR-5429 1.4.6; the return of MODEL-EQUATIONS.md, FLAC's convention: tension
// positive, principal stresses s1 <= s2 <= s3). The three principal stresses include szz: the
// reference orders the in-plane two only; here szz takes part, so that a zone whose szz is the
// smallest or largest principal stress fails on the right pair.
#include <algorithm>
#include <cmath>
#include <cstdint>

namespace vdec {

struct MohrCoulombProperties {
  double nPhi = 1.0, nPsi = 1.0;  // (1 + sin x) / (1 - sin x) of friction and dilation
  double cohesion = 0.0;          // Pa
  double tension = 0.0;           // tensile strength (cut-off), Pa
};

// Plastic state of a zone this step.
enum PlasticState : std::uint8_t { Elastic = 0, ShearNow = 1, TensionNow = 2, PlasticInPast = 4 };

// The elastic response D n to the shear flow of the main face (s1, s3), n = (1, 0, -N_psi), D
// the elastic matrix (a1 on the diagonal, a2 off it).
inline void mainFaceResponse(double a1, double a2, double nPsi, double dn[3]) {
  dn[0] = a1 - a2 * nPsi;
  dn[1] = a2 * (1.0 - nPsi);
  dn[2] = a2 - a1 * nPsi;
}

// The shear criterion f = s1 - s3 N_phi + 2 c sqrt(N_phi), negative beyond the surface.
inline double shearCriterion(const MohrCoulombProperties& mc, double s1, double s3) {
  return s1 - s3 * mc.nPhi + 2.0 * mc.cohesion * std::sqrt(mc.nPhi);
}

// The corrections d to the ordered principal stresses s1 <= s2 <= s3 that return them onto the
// shear yield surface, f = s1 - s3 N_phi + 2 c sqrt(N_phi) < 0 at the trial (fs), with the
// flow g = s1 - s3 N_psi: d = -lambda D n, n = (1, 0, -N_psi), D the elastic matrix (a1 on
// the diagonal, a2 off it). Where that return would cross the order of the principal stresses,
// the stress belongs on an edge of the yield surface, where a second face is active too: the
// face of (s2, s3) when s1 would pass s2, of (s1, s2) when s2 would pass s3. Both faces'
// consistency conditions then give the two multipliers (de Souza Neto, Peric and Owen,
// Computational Methods for Plasticity, 2008, section 8.2.2), and the edge's two stresses come
// out equal.
inline void shearReturn(const MohrCoulombProperties& mc, double a1, double a2, double s1, double s2, double s3,
                        double fs, double d[3]) {
  const double nPhi = mc.nPhi, nPsi = mc.nPsi;
  double dnMain[3];
  mainFaceResponse(a1, a2, nPsi, dnMain);
  const double onMain = dnMain[0] - nPhi * dnMain[2];                            // its m . D n
  const double lambda = fs / onMain;
  for (int i = 0; i < 3; ++i) d[i] = -lambda * dnMain[i];
  const bool pastS2 = s1 + d[0] > s2 + d[1], pastS3 = s2 + d[1] > s3 + d[2];
  if (!pastS2 && !pastS3) return;
  // The second face, its D n, the cross terms m_main . D n_second (= m_second . D n_main) and
  // its trial value.
  double dnSecond[3], cross, fSecond;
  if (pastS2) {  // face (2, 3): n = (0, 1, -N_psi), f = s2 - s3 N_phi + k
    dnSecond[0] = a2 * (1.0 - nPsi);
    dnSecond[1] = a1 - a2 * nPsi;
    dnSecond[2] = a2 - a1 * nPsi;
    cross = dnSecond[0] - nPhi * dnSecond[2];
    fSecond = shearCriterion(mc, s2, s3);
  } else {  // face (1, 2): n = (1, -N_psi, 0), f = s1 - s2 N_phi + k
    dnSecond[0] = a1 - a2 * nPsi;
    dnSecond[1] = a2 - a1 * nPsi;
    dnSecond[2] = a2 * (1.0 - nPsi);
    cross = dnSecond[0] - nPhi * dnSecond[2];
    fSecond = shearCriterion(mc, s1, s2);
  }
  // [onMain cross; cross onMain] (lambda_main, lambda_second) = (fs, fSecond): the two faces are
  // alike, so the system is symmetric with equal diagonal.
  const double det = onMain * onMain - cross * cross;
  const double lambdaMain = (onMain * fs - cross * fSecond) / det;
  const double lambdaSecond = (onMain * fSecond - cross * fs) / det;
  for (int i = 0; i < 3; ++i) d[i] = -lambdaMain * dnMain[i] - lambdaSecond * dnSecond[i];
}

// Near the apex a face return can end beyond the other surface: the shear return with its
// largest stress above the tensile strength, or the tension return with the shear criterion
// violated. The stress then belongs on the corner of the shear face and the tension plane, and
// the two consistency conditions, with the shear flow n_s = (1, 0, -N_psi) and the tension flow
// n_t = (0, 0, -1), give the two multipliers:
//   fs - l_s m_s.D n_s - l_t m_s.D n_t = 0,   ft - l_s m_t.D n_s - l_t m_t.D n_t = 0.
// The intermediate stress, held by neither surface, is kept between the other two.
inline std::uint8_t cornerReturn(const MohrCoulombProperties& mc, double a1, double a2, double s1, double s2, double s3,
                                 double fs, double ft, double d[3]) {
  const double nPhi = mc.nPhi;
  double dnS[3];
  mainFaceResponse(a1, a2, mc.nPsi, dnS);
  const double dnT[3] = {-a2, -a2, -a1};
  const double ss = dnS[0] - nPhi * dnS[2], st = dnT[0] - nPhi * dnT[2];  // m_s = (1, 0, -N_phi)
  const double ts = -dnS[2], tt = -dnT[2];                                // m_t = (0, 0, -1)
  const double det = ss * tt - st * ts;
  const double lS = (fs * tt - st * ft) / det, lT = (ss * ft - ts * fs) / det;
  for (int i = 0; i < 3; ++i) d[i] = -lS * dnS[i] - lT * dnT[i];
  d[1] = std::clamp(s2 + d[1], s1 + d[0], s3 + d[2]) - s2;
  return ShearNow | TensionNow;
}

// Corrects the trial stress (sxx, syy, sxy, szz) onto the yield surface; a1 = K + 4G/3,
// a2 = K - 2G/3. Returns ShearNow, TensionNow or Elastic.
inline std::uint8_t mohrCoulombReturn(const MohrCoulombProperties& mc, double a1, double a2, double& sxx, double& syy,
                                      double& sxy, double& szz) {
  // In-plane principal stresses sa <= sb about the in-plane centre c, radius r.
  const double c = 0.5 * (sxx + syy), dx = 0.5 * (sxx - syy);
  const double r = std::sqrt(dx * dx + sxy * sxy);
  double p[3] = {c - r, c + r, szz};  // a, b, z
  int order[3] = {0, 1, 2};
  std::sort(order, order + 3, [&](int i, int j) { return p[i] < p[j]; });
  const double s1 = p[order[0]], s3 = p[order[2]];
  const double sqrtNPhi = std::sqrt(mc.nPhi);
  const double fs = shearCriterion(mc, s1, s3);
  const double ft = mc.tension - s3;
  if (fs >= 0.0 && ft >= 0.0) return Elastic;
  // Which surface: h = 0 is the diagonal between the shear and tension yield lines in the
  // (s1, s3) plane (FLAC); tension only where the cut-off is itself violated.
  const double alphaP = std::sqrt(1.0 + mc.nPhi * mc.nPhi) + mc.nPhi;
  const double sigmaP = mc.tension * mc.nPhi - 2.0 * mc.cohesion * sqrtNPhi;
  const double h = s3 - mc.tension + alphaP * (s1 - sigmaP);
  double d[3];  // corrections to (s1, s2, s3)
  std::uint8_t state;
  if (ft < 0.0 && h > 0.0) {
    // Tension: flow g = -s3; the correction lambda (a2, a2, a1) with lambda = ft / a1.
    const double lambda = ft / a1;
    d[0] = lambda * a2;
    d[1] = lambda * a2;
    d[2] = lambda * a1;
    // Where s2 too would stay above the cut-off, both are returned onto it, each with its own
    // tension flow: D (l2 e2 + l3 e3) = (T - s2, T - s3) on those two, a1 on the diagonal and
    // a2 off it; s1 moves by a2 (l2 + l3).
    const double s2 = p[order[1]];
    if (s2 + d[1] > mc.tension) {
      const double det = a1 * a1 - a2 * a2;
      const double g2 = mc.tension - s2, g3 = ft;
      const double l2 = (a1 * g2 - a2 * g3) / det, l3 = (a1 * g3 - a2 * g2) / det;
      d[1] = g2;
      d[2] = g3;
      // And all three at T where s1 would end above it too.
      d[0] = std::min(a2 * (l2 + l3), mc.tension - s1);
    }
    state = TensionNow;
    if (shearCriterion(mc, s1 + d[0], s3 + d[2]) < 0.0)
      state = cornerReturn(mc, a1, a2, p[order[0]], p[order[1]], s3, fs, ft, d);
  } else {
    shearReturn(mc, a1, a2, p[order[0]], p[order[1]], s3, fs, d);
    state = ShearNow;
    if (s3 + d[2] > mc.tension) state = cornerReturn(mc, a1, a2, p[order[0]], p[order[1]], s3, fs, ft, d);
  }
  for (int k = 0; k < 3; ++k) p[order[k]] += d[k];
  // Back to x, y: the principal directions are kept (the correction is coaxial).
  const double c2 = 0.5 * (p[0] + p[1]), r2 = 0.5 * (p[1] - p[0]);
  if (r > 0.0) {
    const double scale = r2 / r;
    sxx = c2 + scale * dx;
    syy = c2 - scale * dx;
    sxy = scale * sxy;
  } else {
    sxx = c2 + r2;
    syy = c2 - r2;
    sxy = 0.0;
  }
  szz = p[2];
  return state;
}

}  // namespace vdec
