#pragma once
// Boundary stiffness of the elastic region outside the block model by the direct boundary
// element method of NUREG/CR-5429 1.4.5 (1.4-60 to 1.4-104): linear isoparametric elements,
// Kelvin's plane-strain fundamental solution, or Melan's half-plane solution (Kelvin's plus
// the complementary part of Telles and Brebbia 1981), collocation at the nodes, free terms
// from rigid-body translation (Cruse 1974). docs/models/boundary-elements.md.
//
// Only the kernel: nothing here is coupled to the blocks yet.
#include <Eigen/Dense>
#include <vector>

#include "core/vec2.hpp"

namespace vdec {

// The far field: isotropic, linear elastic, plane strain.
struct ElasticRegion {
  double young = 0.0;
  double poisson = 0.0;
  bool halfPlane = false;  // the region lies below the free surface y = surfaceY
  double surfaceY = 0.0;
};

// The influence matrices of 1.4-67, [T]{u} = [U]{t}, and the consistent nodal-force matrix
// of the linear tractions, {q} = [M]{t} (1.4-68). Unknowns ordered x0, y0, x1, y1, ...
// t is the traction the blocks exert on the region (its outward normal points into the blocks).
struct BoundaryElementMatrices {
  Eigen::MatrixXd traction;      // [T], the free terms on its 2x2 diagonal blocks
  Eigen::MatrixXd displacement;  // [U]
  Eigen::MatrixXd nodalForce;    // [M]
  double referenceLength = 1.0;  // the unit of length of the kernels' logarithm (see below)
};

// nodes: the interface points in order along the boundary of the block model, counter-clockwise
// around the blocks, so that the elastic region lies to the right of the direction of travel.
// closed = true: a closed loop in the infinite plane (at least 3 nodes). For the half-plane an
// open chain (at least 2 nodes) whose two end nodes lie on the free surface y = surfaceY and
// whose other nodes lie below it; the surface carries no elements.
// Throws SceneError for bad elastic constants, GeometryError for bad nodes.
// Cost: O(n^2) element integrals (each a fixed number of Gauss points, more on elements close
// to the collocation node); memory: three 2n x 2n matrices.
BoundaryElementMatrices assembleBoundaryElements(const std::vector<Vec2>& nodes, bool closed,
                                                 const ElasticRegion& region);

// K (2n x 2n) such that the forces per unit thickness the region exerts ON the interface nodes
// are f = -K u for nodal displacements u (linear between nodes): K = [M][U]^-1[T] (1.4-70 to
// 1.4-72), from a dense LU factorisation of [U] and its solve with [T]'s 2n columns, O(n^3);
// memory at the peak about 6 (2n)^2 doubles ([T], [U], [M], [U]'s LU factors, [U]^-1[T], K).
// Displacements are those of the boundary integral equation, whose reference is the point at
// infinity in the sense of the kernels' logarithm ln(r / L0), L0 = 10 times the nodes' largest
// distance from their centroid: a rigid translation of the nodes is resisted (a field with a
// net force grows like ln r in 2D; docs/models/boundary-elements.md#derivation). L0 keeps the
// boundary far from the degenerate scale where [U] is singular, and makes K independent of the
// unit of length. A condition estimate of [U] below 1e-13 throws InstabilityError.
Eigen::MatrixXd boundaryStiffness(const std::vector<Vec2>& nodes, bool closed,
                                  const ElasticRegion& region);

// The stiffness of 1.4-98 to 1.4-101: forces for nodal displacements u with the region's point
// fixedPoint held fixed instead of the point at infinity (Lemos 1983). The point must lie in
// the elastic region, away from the boundary. Independent of the unit of length.
Eigen::MatrixXd boundaryStiffnessWithFixedPoint(const std::vector<Vec2>& nodes, bool closed,
                                                const ElasticRegion& region, Vec2 fixedPoint);

// The displacement at a point of the region (1.4-77, Somigliana's identity) for nodal
// displacements u, with the tractions of [U]{t} = [T]{u}: a 2 x 2n matrix D, u_point = D u.
Eigen::MatrixXd interiorDisplacementOperator(const std::vector<Vec2>& nodes, bool closed,
                                             const ElasticRegion& region, Vec2 point);

// The fundamental solution: U[l][k], T[l][k] the displacement and the traction (on a surface
// of unit normal `normal`) in direction k at `field` due to a unit force in direction l at
// `source` (x = 0, y = 1). Kelvin's (1.4-81, 1.4-82), or Melan's for the half-plane
// (1.4-84, 1.4-85 added). Exposed for the unit tests.
struct KernelValues {
  double U[2][2];
  double T[2][2];
};
// referenceLength: the unit of length of the logarithms, ln(r / referenceLength).
KernelValues fundamentalSolution(const ElasticRegion& region, Vec2 source, Vec2 field,
                                 Vec2 normal, double referenceLength = 1.0);

// Integrals over the straight element a-b (normal: perp(b - a), unit) of the kernels times the
// linear shape functions N_a = (1 - s), N_b = s: U[node][l][k], T[node][l][k]. When the source
// is a (or b), `sourceAtEnd` = 0 (or 1): U's logarithm is integrated in closed form and T only
// against the other node's shape function (the singular part goes to the free terms).
// sourceAtEnd = -1: the source is off the element. Exposed for the unit tests.
struct ElementIntegrals {
  double U[2][2][2];
  double T[2][2][2];
};
ElementIntegrals integrateElement(const ElasticRegion& region, Vec2 source, Vec2 a, Vec2 b,
                                  int sourceAtEnd, double referenceLength = 1.0);

}  // namespace vdec
