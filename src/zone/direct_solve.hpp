#pragma once
// The linear static problem of the elastic zones, solved directly: the stiffness of the
// constant-strain triangles assembled on the current configuration, K du = f_external +
// f_zones, solved by sparse Cholesky (Eigen's SimplicialLDLT) over the free gridpoint
// components. Used as an oracle in tests (dynamic relaxation must reach the same equilibrium)
// and, when a scene asks for it, as a fast path: the run starts from the direct solution and
// continues with explicit cycles, which then only have the nonlinear remainder to remove.
#include "core/model.hpp"

namespace vdec {

struct DirectSolveReport {
  int unknowns = 0;
  int solves = 0;  // on successive configurations, until the residual is at round-off
  int factorisations = 0;  // of the stiffness: once, and again when the joints carrying springs change
  int plasticIterations = 0;  // of the plastic zones' equilibrium, over all solves (0 without plastic zones)
  bool plasticConverged = true;  // false when the iteration gave up without an equilibrium (stagnant or at its limit)
  double plasticResidual = 0.0;  // its last residual, N/m
  double relativeResidual = 0.0;  // of the last solve's right-hand side, over the force scale
  double seconds = 0.0;
  double largestDisplacement = 0.0;
};

// Solves for the displacement that balances gravity, the boundary tractions and the present
// zone stresses, and applies it: gridpoints move, zone stresses take the elastic increment,
// velocities become zero. Throws SceneError when a gridpoint component is driven at a nonzero
// velocity (no static meaning) or the zones are not held against rigid-body motion.
DirectSolveReport solveStaticDirect(Model& model);

}  // namespace vdec
