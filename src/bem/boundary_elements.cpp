// The direct boundary element method of NUREG/CR-5429 1.4.5 for the elastic region outside the
// block model. Derivation, accuracy and limits: docs/models/boundary-elements.md.
//
// Notation. A unit force in direction l at the source xi; at a field point x, U[l][k] is the
// displacement and T[l][k] the traction (on the boundary's normal n) in direction k. The
// boundary integral equation at node i (1.4-64, 1.4-65), with n the region's outward normal
// (pointing into the blocks) and t = sigma n the traction the blocks exert on the region:
//   c_lk(i) u_k(i) + PV int_S T_lk u_k dS = int_S U_lk t_k dS.
//
// Free terms of an EXTERIOR region (1.4-91 to 1.4-95). Take the region bounded by S and a large
// circle S_R. A rigid translation u = e, t = 0 solves the elastic equations, so
//   c_lk(i) + PV int_S T_lk dS + int_{S_R} T_lk dS = 0.
// The traction of the unit force integrated over any curve enclosing it (normal pointing out
// of the curve) balances it: int_{S_R} T_lk dS = -delta_lk (1.4-95), for Kelvin's solution and,
// the free surface carrying no traction, for Melan's on the half-circle. Hence
//   c_lk(i) = delta_lk - PV int_S T_lk dS,
// so the rows of [T] sum to the identity: [T] e = e for a translation e, not [T] e = 0 as for a
// bounded (interior) region, and the diagonal blocks come from the off-diagonal ones:
//   [T]_ii = I - sum_{j != i} [T]_ij.
// A consequence: the translation gives the tractions t = [U]^-1 e, not zero. The equation holds
// for fields whose displacement vanishes at infinity in the sense of the fundamental solution's
// logarithm, ln(r / L0); in 2D a field carrying a net force grows like ln r, so moving the
// boundary by e "relative to infinity" is resisted by a finite force that depends on L0 (a
// rigid disc of radius a: net force 16 pi G (1 - nu) e / (1 + 2 (3 - 4 nu) ln(L0 / a))).
// L0 (referenceLengthOf) is tied to the boundary's size, so K does not depend on the unit of
// length. 1.4-98 to 1.4-101 replace the point at infinity by a fixed point P of the region:
// boundaryStiffnessWithFixedPoint.
//
// Quadrature. Off the source, Gauss-Legendre (10 points) on equal sub-intervals no longer than
// half the source's distance to the element. On the two elements meeting at the source,
// Kelvin's logarithm times the shape functions is integrated in closed form (not Anderson's
// log-weighted rule: on a straight element r = s L exactly), as is Kelvin's traction against
// the far node's shape function (only its antisymmetric 1/r term survives, dr/dn = 0); the
// traction against the source node's own shape function, the Cauchy principal value, is never
// computed: it is in [T]_ii. Melan's complementary part is regular unless the source lies on
// the free surface (the chain's end nodes), where it is ln R and 1/R singular; it is
// integrated on sub-intervals graded geometrically towards the source.
#include "bem/boundary_elements.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <Eigen/SparseCore>
#include <numbers>
#include <sstream>
#include <string>

#include "core/errors.hpp"

namespace vdec {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr int kGaussPoints = 10;

struct GaussRule {
  std::array<double, kGaussPoints> abscissa{};  // on [0, 1]
  std::array<double, kGaussPoints> weight{};
};

// Gauss-Legendre on [0, 1]: Newton's iteration on the Legendre polynomial's roots.
GaussRule makeGaussRule() {
  GaussRule rule;
  const int n = kGaussPoints;
  for (int i = 0; i < n; ++i) {
    double x = std::cos(kPi * (i + 0.75) / (n + 0.5));
    double derivative = 1.0;
    for (int iteration = 0; iteration < 100; ++iteration) {
      double p0 = 1.0;
      double p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      derivative = n * (x * p1 - p0) / (x * x - 1.0);
      const double step = p1 / derivative;
      x -= step;
      if (std::abs(step) < 1e-16) break;
    }
    rule.abscissa[i] = 0.5 * (1.0 - x);
    rule.weight[i] = 1.0 / ((1.0 - x * x) * derivative * derivative);
  }
  return rule;
}

const GaussRule& gaussRule() {
  static const GaussRule rule = makeGaussRule();
  return rule;
}

struct Elastic {
  double shear;
  double nu;
  double kd;               // 1 / (8 pi G (1 - nu)), 1.4-83
  double logOfReference;   // ln of the logarithm's unit of length
};

Elastic elasticOf(const ElasticRegion& region, double referenceLength) {
  const double shear = region.young / (2.0 * (1.0 + region.poisson));
  return {shear, region.poisson, 1.0 / (8.0 * kPi * shear * (1.0 - region.poisson)),
          std::log(referenceLength)};
}

// Kelvin's plane-strain solution, 1.4-81 and 1.4-82; its traction from the stresses of 1.4-86
// on the normal n: T_lk = -1 / (4 pi (1 - nu) r) { dr/dn [(1 - 2 nu) d_lk + 2 r_l r_k]
//                                                  - (1 - 2 nu) (r_l n_k - r_k n_l) }.
void addKelvin(const Elastic& e, Vec2 source, Vec2 field, Vec2 normal, KernelValues& out) {
  const Vec2 d = field - source;
  const double r = norm(d);
  const double rl[2] = {d.x / r, d.y / r};
  const double n[2] = {normal.x, normal.y};
  const double drdn = rl[0] * n[0] + rl[1] * n[1];
  const double logTerm = -(3.0 - 4.0 * e.nu) * (std::log(r) - e.logOfReference);
  const double tScale = -1.0 / (4.0 * kPi * (1.0 - e.nu) * r);
  for (int l = 0; l < 2; ++l) {
    for (int k = 0; k < 2; ++k) {
      const double delta = l == k ? 1.0 : 0.0;
      out.U[l][k] += e.kd * (logTerm * delta + rl[l] * rl[k]);
      out.T[l][k] += tScale * (drdn * ((1.0 - 2.0 * e.nu) * delta + 2.0 * rl[l] * rl[k]) -
                               (1.0 - 2.0 * e.nu) * (rl[l] * n[k] - rl[k] * n[l]));
    }
  }
}

// Melan's complementary part (Telles and Brebbia 1981; 1.4-84, 1.4-85), in the frame of the
// half-plane: x1 horizontal, x2 the depth below the surface. Source at depth c, field point at
// horizontal offset r1 and depth d; R1 = r1, R2 = d + c the offsets from the source's image,
// r2 = d - c, theta = atan(R1 / R2), A = 8 (1 - nu)^2 - (3 - 4 nu), B = 4 (1 - nu)(1 - 2 nu):
//   U11 = Kd { -A ln R + [(3 - 4 nu) R1^2 + 2 c d] / R^2 - 4 c d R1^2 / R^4 }
//   U12 = Kd { (3 - 4 nu) R1 r2 / R^2 - 4 c d R1 R2 / R^4 + B theta }
//   U21 = Kd { (3 - 4 nu) R1 r2 / R^2 + 4 c d R1 R2 / R^4 - B theta }
//   U22 = Kd { -A ln R + [(3 - 4 nu) R2^2 - 2 c d] / R^2 + 4 c d R2^2 / R^4 }
// (U[load][displacement]). The reference's OCR loses the signs; these were checked to make
// Kelvin + complement traction-free on the surface, to satisfy Navier's equations and to be
// reciprocal, U_lk(xi, x) = U_kl(x, xi) (tests/unit/test_boundary_elements.cpp). Templated so
// that the stresses come from complex-step derivatives, exact to rounding.
template <class S>
void melanComplement(const Elastic& e, S r1, S d, double c, S U[2][2]) {
  using std::atan;
  using std::log;
  const double nu = e.nu;
  const double a = 8.0 * (1.0 - nu) * (1.0 - nu) - (3.0 - 4.0 * nu);
  const double b = 4.0 * (1.0 - nu) * (1.0 - 2.0 * nu);
  const double k = 3.0 - 4.0 * nu;
  const S R2 = d + c;
  const S r2 = d - c;
  const S R2sq = r1 * r1 + R2 * R2;
  const S R4 = R2sq * R2sq;
  const S logR = 0.5 * log(R2sq) - e.logOfReference;
  const S theta = atan(r1 / R2);
  const S cd = c * d;
  U[0][0] = e.kd * (-a * logR + (k * r1 * r1 + 2.0 * cd) / R2sq - 4.0 * cd * r1 * r1 / R4);
  U[0][1] = e.kd * (k * r1 * r2 / R2sq - 4.0 * cd * r1 * R2 / R4 + b * theta);
  U[1][0] = e.kd * (k * r1 * r2 / R2sq + 4.0 * cd * r1 * R2 / R4 - b * theta);
  U[1][1] = e.kd * (-a * logR + (k * R2 * R2 - 2.0 * cd) / R2sq + 4.0 * cd * R2 * R2 / R4);
}

// The complementary part in the x-y frame (y up): the half-plane frame's x2 is -y, so each
// y component and each y derivative changes sign.
void addMelanComplement(const Elastic& e, double surfaceY, Vec2 source, Vec2 field, Vec2 normal,
                        KernelValues& out) {
  const double c = surfaceY - source.y;
  const double r1 = field.x - source.x;
  const double d = surfaceY - field.y;
  double U[2][2];
  melanComplement<double>(e, r1, d, c, U);
  // Complex step: f'(x) = Im f(x + i h) / h, no cancellation.
  using C = std::complex<double>;
  const double h = 1e-30 * (1.0 + std::abs(r1) + std::abs(d) + c);
  C Ux[2][2];
  C Ud[2][2];
  melanComplement<C>(e, C(r1, h), C(d, 0.0), c, Ux);
  melanComplement<C>(e, C(r1, 0.0), C(d, h), c, Ud);
  const double sign[2] = {1.0, -1.0};
  const double lambda = 2.0 * e.shear * e.nu / (1.0 - 2.0 * e.nu);
  const double n[2] = {normal.x, normal.y};
  for (int l = 0; l < 2; ++l) {
    // grad[k][j] = d u_k / d x_j in the x-y frame for a unit force in direction l (x-y frame).
    double grad[2][2];
    for (int k = 0; k < 2; ++k) {
      grad[k][0] = sign[l] * sign[k] * Ux[l][k].imag() / h;
      grad[k][1] = -sign[l] * sign[k] * Ud[l][k].imag() / h;  // d/dy = -d/dx2
      out.U[l][k] += sign[l] * sign[k] * U[l][k];
    }
    const double divergence = grad[0][0] + grad[1][1];
    for (int k = 0; k < 2; ++k) {
      double traction = 0.0;
      for (int j = 0; j < 2; ++j) {
        const double stress =
            (k == j ? lambda * divergence : 0.0) + e.shear * (grad[k][j] + grad[j][k]);
        traction += stress * n[j];
      }
      out.T[l][k] += traction;
    }
  }
}

KernelValues kernelAt(const Elastic& e, const ElasticRegion& region, Vec2 source, Vec2 field,
                      Vec2 normal, bool withKelvin) {
  KernelValues out{};
  if (withKelvin) addKelvin(e, source, field, normal, out);
  if (region.halfPlane) addMelanComplement(e, region.surfaceY, source, field, normal, out);
  return out;
}

// Adds the integral over the parameter interval [s0, s1] of the element a-b (length L) of the
// kernels times the shape functions (1 - s) and s, with `pieces` equal Gauss sub-intervals.
void addGaussIntegral(const Elastic& e, const ElasticRegion& region, Vec2 source, Vec2 a,
                      Vec2 b, double s0, double s1, int pieces, bool withKelvin,
                      ElementIntegrals& out) {
  const GaussRule& rule = gaussRule();
  const Vec2 chord = b - a;
  const double length = norm(chord);
  const Vec2 normal = (1.0 / length) * perp(chord);
  const double width = (s1 - s0) / pieces;
  for (int p = 0; p < pieces; ++p) {
    for (int g = 0; g < kGaussPoints; ++g) {
      const double s = s0 + width * (p + rule.abscissa[g]);
      const double w = width * rule.weight[g] * length;
      const KernelValues kv = kernelAt(e, region, source, a + s * chord, normal, withKelvin);
      const double shape[2] = {1.0 - s, s};
      for (int node = 0; node < 2; ++node) {
        for (int l = 0; l < 2; ++l) {
          for (int k = 0; k < 2; ++k) {
            out.U[node][l][k] += w * shape[node] * kv.U[l][k];
            out.T[node][l][k] += w * shape[node] * kv.T[l][k];
          }
        }
      }
    }
  }
}

double distanceToSegment(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 ab = b - a;
  const double s = std::clamp(dot(p - a, ab) / dot(ab, ab), 0.0, 1.0);
  return norm(p - (a + s * ab));
}

// Sub-intervals no longer than half the source's distance: 10 Gauss points then integrate ln r
// and 1/r to about 1e-14 relative. Capped: a source closer than L/512 to an element it is not a
// node of (two parts of the boundary nearly touching) loses accuracy.
constexpr int kMaxPieces = 1024;

}  // namespace

KernelValues fundamentalSolution(const ElasticRegion& region, Vec2 source, Vec2 field,
                                 Vec2 normal, double referenceLength) {
  return kernelAt(elasticOf(region, referenceLength), region, source, field, normal, true);
}

ElementIntegrals integrateElement(const ElasticRegion& region, Vec2 source, Vec2 a, Vec2 b,
                                  int sourceAtEnd, double referenceLength) {
  const Elastic e = elasticOf(region, referenceLength);
  ElementIntegrals out{};
  const double length = norm(b - a);
  if (sourceAtEnd < 0) {
    const double distance = distanceToSegment(source, a, b);
    if (!(distance > 1e-12 * length)) {
      std::ostringstream msg;
      msg << "boundary elements: the point (" << source.x << ", " << source.y
          << ") lies on the element from (" << a.x << ", " << a.y << ") to (" << b.x << ", "
          << b.y << "): the boundary touches or crosses itself";
      throw GeometryError(msg.str());
    }
    const int pieces =
        std::clamp(static_cast<int>(std::ceil(2.0 * length / distance)), 1, kMaxPieces);
    addGaussIntegral(e, region, source, a, b, 0.0, 1.0, pieces, true, out);
    return out;
  }
  // The source is node `near` (0: a, 1: b); the element's unit direction t, r = s' L with s'
  // the parameter measured from the source.
  const int near = sourceAtEnd;
  const int far = 1 - near;
  const Vec2 t = (1.0 / length) * (b - a);
  const Vec2 normal = perp(t);
  const Vec2 rhat = near == 0 ? t : -1.0 * t;
  const double tv[2] = {t.x, t.y};
  const double rv[2] = {rhat.x, rhat.y};
  const double nv[2] = {normal.x, normal.y};
  // int_0^1 ln(s L) (1 - s) L ds = L (ln L / 2 - 3/4), int_0^1 ln(s L) s L ds = L (ln L / 2 - 1/4),
  // L in units of the reference length.
  const double logLength = std::log(length) - e.logOfReference;
  const double logNear = length * (0.5 * logLength - 0.75);
  const double logFar = length * (0.5 * logLength - 0.25);
  // Kelvin's T against the far node's shape function s: dr/dn = 0 on the element, so
  // T_lk s = (1 - 2 nu) (r_l n_k - r_k n_l) s / (4 pi (1 - nu) s L), integrated over L ds.
  const double tFar = (1.0 - 2.0 * e.nu) / (4.0 * kPi * (1.0 - e.nu));
  for (int l = 0; l < 2; ++l) {
    for (int k = 0; k < 2; ++k) {
      const double delta = l == k ? 1.0 : 0.0;
      const double dyad = 0.5 * length * tv[l] * tv[k];  // r_l r_k constant, times int N ds
      out.U[near][l][k] = e.kd * (-(3.0 - 4.0 * e.nu) * logNear * delta + dyad);
      out.U[far][l][k] = e.kd * (-(3.0 - 4.0 * e.nu) * logFar * delta + dyad);
      out.T[far][l][k] = tFar * (rv[l] * nv[k] - rv[k] * nv[l]);
    }
  }
  if (region.halfPlane) {
    // The complement: smooth for a source below the surface, ln R and 1/R singular at a source
    // on it. Sub-intervals [s/2, s] of the parameter s measured from the source (10 Gauss points
    // integrate ln on such an interval to about 1e-15), down to 1e-14: the rest, [0, 1e-14],
    // holds under 1e-12 of the integral of ln(s L) and is left out (closer, the field point
    // would round onto the source).
    ElementIntegrals complement{};
    const Vec2 from = near == 0 ? a : b;
    const Vec2 to = near == 0 ? b : a;
    constexpr double ratio = 0.5;
    constexpr int levels = 47;  // 0.5^47 = 7e-15
    double upper = 1.0;
    for (int m = 0; m < levels; ++m) {
      const double lower = upper * ratio;
      addGaussIntegral(e, region, source, from, to, lower, upper, 1, false, complement);
      upper = lower;
    }
    // complement's node 0 is `from` (the source); map back to a-b numbering. The direction of
    // travel from-to reverses the normal when near == 1: T is linear in the normal.
    const double normalSign = near == 0 ? 1.0 : -1.0;
    for (int l = 0; l < 2; ++l) {
      for (int k = 0; k < 2; ++k) {
        out.U[near][l][k] += complement.U[0][l][k];
        out.U[far][l][k] += complement.U[1][l][k];
        out.T[far][l][k] += normalSign * complement.T[1][l][k];
      }
    }
  }
  return out;
}

namespace {

void checkInput(const std::vector<Vec2>& nodes, bool closed, const ElasticRegion& region) {
  if (!(region.young > 0.0) || !std::isfinite(region.young)) {
    throw SceneError("boundary elements: Young's modulus of the elastic region must be > 0 (got " +
                     std::to_string(region.young) + ")");
  }
  if (!(region.poisson >= 0.0 && region.poisson < 0.5)) {
    throw SceneError("boundary elements: Poisson's ratio of the elastic region must be in [0, 0.5) (got " +
                     std::to_string(region.poisson) + ")");
  }
  const std::size_t n = nodes.size();
  if (closed && n < 3) {
    throw GeometryError("boundary elements: a closed boundary needs at least 3 nodes (got " +
                        std::to_string(n) + ")");
  }
  if (!closed && n < 2) {
    throw GeometryError("boundary elements: an open boundary needs at least 2 nodes (got " +
                        std::to_string(n) + ")");
  }
  if (region.halfPlane == closed) {
    throw GeometryError(region.halfPlane
                            ? "boundary elements: the half-plane's boundary is an open chain from "
                              "the free surface to the free surface (closed = false)"
                            : "boundary elements: the infinite plane's boundary is a closed loop "
                              "(closed = true)");
  }
  double extent = 0.0;
  for (const Vec2& p : nodes) extent = std::max({extent, std::abs(p.x), std::abs(p.y)});
  const std::size_t elements = closed ? n : n - 1;
  for (std::size_t i = 0; i < elements; ++i) {
    if (norm(nodes[(i + 1) % n] - nodes[i]) <= 1e-12 * std::max(extent, 1.0)) {
      throw GeometryError("boundary elements: nodes " + std::to_string(i) + " and " +
                          std::to_string((i + 1) % n) + " coincide; remove one");
    }
  }
  if (region.halfPlane) {
    const double tolerance = 1e-9 * std::max(extent, 1.0);
    for (std::size_t i = 0; i < n; ++i) {
      const double depth = region.surfaceY - nodes[i].y;
      const bool end = i == 0 || i + 1 == n;
      if (end && std::abs(depth) > tolerance) {
        std::ostringstream m;
        m << "boundary elements: end node " << i << " (" << nodes[i].x << ", " << nodes[i].y
          << ") must lie on the free surface y = " << region.surfaceY;
        throw GeometryError(m.str());
      }
      if (!end && depth <= tolerance) {
        std::ostringstream m;
        m << "boundary elements: node " << i << " (" << nodes[i].x << ", " << nodes[i].y
          << ") must lie below the free surface y = " << region.surfaceY;
        throw GeometryError(m.str());
      }
    }
  }
}

// The logarithm's unit of length: ten times the nodes' largest distance from their centroid.
// In this unit the boundary is far smaller than the degenerate scale of the logarithmic kernel
// (about 1 for any shape: a circle of radius exp(1 / (2 (3 - 4 nu))), 1.18 to 1.65), where [U]
// is singular, and K does not depend on the user's unit of length.
double referenceLengthOf(const std::vector<Vec2>& nodes) {
  Vec2 centroid{};
  for (const Vec2& p : nodes) centroid += p;
  centroid = (1.0 / static_cast<double>(nodes.size())) * centroid;
  double radius = 0.0;
  for (const Vec2& p : nodes) radius = std::max(radius, norm(p - centroid));
  return 10.0 * radius;
}

// End nodes on the free surface sit exactly on it: the complement's depth c = 0 there.
Vec2 sourceOf(const std::vector<Vec2>& nodes, std::size_t i, bool closed,
              const ElasticRegion& region) {
  Vec2 p = nodes[i];
  if (region.halfPlane && !closed && (i == 0 || i + 1 == nodes.size())) p.y = region.surfaceY;
  return p;
}

}  // namespace

BoundaryElementMatrices assembleBoundaryElements(const std::vector<Vec2>& nodes, bool closed,
                                                 const ElasticRegion& region) {
  checkInput(nodes, closed, region);
  const std::size_t n = nodes.size();
  const std::size_t elements = closed ? n : n - 1;
  const Eigen::Index size = static_cast<Eigen::Index>(2 * n);
  BoundaryElementMatrices m{Eigen::MatrixXd::Zero(size, size), Eigen::MatrixXd::Zero(size, size),
                            Eigen::MatrixXd::Zero(size, size), referenceLengthOf(nodes)};
  std::vector<Vec2> points(n);
  for (std::size_t i = 0; i < n; ++i) points[i] = sourceOf(nodes, i, closed, region);

  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t el = 0; el < elements; ++el) {
      const std::size_t na = el;
      const std::size_t nb = (el + 1) % n;
      const int sourceAtEnd = i == na ? 0 : (i == nb ? 1 : -1);
      const ElementIntegrals ei =
          integrateElement(region, points[i], points[na], points[nb], sourceAtEnd,
                           m.referenceLength);
      const std::size_t columnNode[2] = {na, nb};
      for (int node = 0; node < 2; ++node) {
        const Eigen::Index column = static_cast<Eigen::Index>(2 * columnNode[node]);
        for (int l = 0; l < 2; ++l) {
          const Eigen::Index row = static_cast<Eigen::Index>(2 * i) + l;
          for (int k = 0; k < 2; ++k) {
            m.displacement(row, column + k) += ei.U[node][l][k];
            // [T]_ii is the free term plus the principal value: set below from the rows' sums.
            if (columnNode[node] != i) m.traction(row, column + k) += ei.T[node][l][k];
          }
        }
      }
    }
    // Rigid translation of the exterior region: [T] e = e (see the comment at the top).
    for (int l = 0; l < 2; ++l) {
      const Eigen::Index row = static_cast<Eigen::Index>(2 * i) + l;
      for (int k = 0; k < 2; ++k) {
        double offDiagonal = 0.0;
        for (std::size_t j = 0; j < n; ++j) {
          if (j != i) offDiagonal += m.traction(row, static_cast<Eigen::Index>(2 * j) + k);
        }
        m.traction(row, static_cast<Eigen::Index>(2 * i) + k) = (l == k ? 1.0 : 0.0) - offDiagonal;
      }
    }
  }
  // 1.4-68: the force at a node from tractions linear along its elements, L/6 [2 1; 1 2].
  for (std::size_t el = 0; el < elements; ++el) {
    const std::size_t na = el;
    const std::size_t nb = (el + 1) % n;
    const double sixth = norm(points[nb] - points[na]) / 6.0;
    for (int k = 0; k < 2; ++k) {
      const Eigen::Index ia = static_cast<Eigen::Index>(2 * na) + k;
      const Eigen::Index ib = static_cast<Eigen::Index>(2 * nb) + k;
      m.nodalForce(ia, ia) += 2.0 * sixth;
      m.nodalForce(ib, ib) += 2.0 * sixth;
      m.nodalForce(ia, ib) += sixth;
      m.nodalForce(ib, ia) += sixth;
    }
  }
  return m;
}

namespace {

// [U]^-1 [T]: the tractions of nodal displacements.
Eigen::MatrixXd tractionsOfDisplacements(const BoundaryElementMatrices& m) {
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(m.displacement);
  const double rcond = lu.rcond();
  if (!(rcond > 1e-13)) {
    std::ostringstream msg;
    msg << "boundary elements: the displacement influence matrix [U] is singular (condition "
           "estimate "
        << rcond << "): check that the boundary does not cross or touch itself";
    throw InstabilityError(msg.str());
  }
  return lu.solve(m.traction);
}

// The region is where the winding number of the blocks' outline (the half-plane's chain closed
// along the surface) is zero, below the surface for the half-plane.
bool insideRegion(const std::vector<Vec2>& nodes, const ElasticRegion& region, Vec2 p) {
  if (region.halfPlane && p.y >= region.surfaceY) return false;
  double winding = 0.0;
  const std::size_t n = nodes.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 a = nodes[i] - p;
    const Vec2 b = nodes[(i + 1) % n] - p;
    winding += std::atan2(cross(a, b), dot(a, b));
  }
  return std::abs(winding) < kPi;
}

// 1.4-76, 1.4-77: u(P) = int U t dS - int T u dS, with t = tractions u.
Eigen::MatrixXd displacementAtPoint(const BoundaryElementMatrices& m,
                                    const Eigen::MatrixXd& tractions,
                                    const std::vector<Vec2>& nodes, bool closed,
                                    const ElasticRegion& region, Vec2 point) {
  if (!insideRegion(nodes, region, point)) {
    std::ostringstream msg;
    msg << "boundary elements: the point (" << point.x << ", " << point.y
        << ") is not in the elastic region (outside the blocks"
        << (region.halfPlane ? ", below the free surface)" : ")") << "; move it there";
    throw GeometryError(msg.str());
  }
  const std::size_t n = nodes.size();
  const std::size_t elements = closed ? n : n - 1;
  const Eigen::Index size = static_cast<Eigen::Index>(2 * n);
  Eigen::MatrixXd integralU = Eigen::MatrixXd::Zero(2, size);
  Eigen::MatrixXd integralT = Eigen::MatrixXd::Zero(2, size);
  for (std::size_t el = 0; el < elements; ++el) {
    const std::size_t columnNode[2] = {el, (el + 1) % n};
    const ElementIntegrals ei = integrateElement(region, point, nodes[columnNode[0]],
                                                 nodes[columnNode[1]], -1, m.referenceLength);
    for (int node = 0; node < 2; ++node) {
      for (int l = 0; l < 2; ++l) {
        for (int k = 0; k < 2; ++k) {
          const Eigen::Index column = static_cast<Eigen::Index>(2 * columnNode[node]) + k;
          integralU(l, column) += ei.U[node][l][k];
          integralT(l, column) += ei.T[node][l][k];
        }
      }
    }
  }
  return integralU * tractions - integralT;
}

}  // namespace

Eigen::MatrixXd boundaryStiffness(const std::vector<Vec2>& nodes, bool closed,
                                  const ElasticRegion& region) {
  const BoundaryElementMatrices m = assembleBoundaryElements(nodes, closed, region);
  // 1.4-70 to 1.4-72: the force on the region is M t = M U^-1 T u; on the nodes, its opposite.
  // M is banded: its sparse product costs O(n^2), not a dense product's O(n^3).
  return m.nodalForce.sparseView() * tractionsOfDisplacements(m);
}

Eigen::MatrixXd interiorDisplacementOperator(const std::vector<Vec2>& nodes, bool closed,
                                             const ElasticRegion& region, Vec2 point) {
  const BoundaryElementMatrices m = assembleBoundaryElements(nodes, closed, region);
  return displacementAtPoint(m, tractionsOfDisplacements(m), nodes, closed, region, point);
}

Eigen::MatrixXd boundaryStiffnessWithFixedPoint(const std::vector<Vec2>& nodes, bool closed,
                                                const ElasticRegion& region, Vec2 fixedPoint) {
  // 1.4-98 to 1.4-101: to the displacements u add the translation a of every node that keeps P
  // where the boundary integral equation's field puts it relative to the nodes:
  //   D (u + E a) - a = 0,  a = -(D E - I)^-1 D u,
  // with D the displacement at P (1.4-77) and E the 2n x 2 matrix of unit translations. The
  // field of u + E a, shifted by -a, has boundary displacement u and P fixed; its forces are
  // K (u + E a) (a translation of the whole field changes no traction).
  const BoundaryElementMatrices m = assembleBoundaryElements(nodes, closed, region);
  const Eigen::MatrixXd tractions = tractionsOfDisplacements(m);
  const Eigen::MatrixXd stiffness = m.nodalForce.sparseView() * tractions;
  const Eigen::MatrixXd atPoint =
      displacementAtPoint(m, tractions, nodes, closed, region, fixedPoint);
  const Eigen::Index size = stiffness.rows();
  Eigen::MatrixXd translations = Eigen::MatrixXd::Zero(size, 2);
  for (Eigen::Index i = 0; i < size; i += 2) {
    translations(i, 0) = 1.0;
    translations(i + 1, 1) = 1.0;
  }
  const Eigen::Matrix2d pointOfTranslation = atPoint * translations - Eigen::Matrix2d::Identity();
  const Eigen::MatrixXd shift = -pointOfTranslation.fullPivLu().solve(atPoint);  // a = shift u
  return stiffness + (stiffness * translations) * shift;
}

}  // namespace vdec
