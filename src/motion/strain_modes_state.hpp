#pragma once
// Simply-deformable blocks (NUREG/CR-5429 1.3.3.3, Fig. 1.3-4; Cundall et al. 1978): a block's
// rigid motion (Blocks) plus three modes of uniform strain in its own frame, e11, e22 and the
// tensor shear e12. A point X of the block (from its centroid, unrotated and unstrained) is at
//   x = c + R(theta) (I + E) X,
// so its velocity is v_c + omega k x (x - c) + R dE/dt X. Plain arrays, part of the Model;
// motion/strain_modes.hpp advances them.
#include <array>
#include <vector>

namespace vdec {

// A symmetric 2x2 tensor in a block's frame: xx, yy and the tensor shear xy.
struct Sym2 {
  double xx = 0.0, yy = 0.0, xy = 0.0;
};

struct StrainModes {
  std::vector<int> of;                 // per block: its index here, -1 for other blocks
  std::vector<int> block;              // per simply-deformable block
  std::vector<double> area;            // of its polygon, m^2
  std::vector<Sym2> strain;            // E, in the block's frame
  std::vector<Sym2> strainRate;        // dE/dt at t - dt/2 before the motion stage, t + dt/2 after
  std::vector<Sym2> stress;            // sigma = D E (plane strain, tension positive), block's frame
  std::vector<double> szz;             // the out-of-plane stress of plane strain
  // Of the block as placed (placeStrainedVertices): cos and sin of its rotation and (I + E)^-1, so
  // that a contact finds its body point without trigonometry or an inversion.
  std::vector<std::array<double, 2>> turn;
  std::vector<Sym2> inverseStretch;
  // The step's generalised strain force of the loads on the block (contacts): for a force f at
  // the body point X, (f'_x X_x, f'_y X_y, f'_x X_y + f'_y X_x), f' = R^T f. A per-step accumulator.
  std::vector<Sym2> force;
  // The consistent mass of (rotation, e11, e22, e12), rho times the integrals over the block of
  // the products of the modes' velocity fields, inverted: row-major 4 x 4; and of the strains
  // alone (3 x 3), for a block whose rotation is driven.
  std::vector<std::array<double, 16>> massInverse;
  std::vector<std::array<double, 9>> strainMassInverse;
  std::vector<std::array<double, 16>> mass;
  int size() const { return static_cast<int>(block.size()); }
  // Whether block b is simply deformable (`of` is empty in a scene without such blocks).
  bool holds(int b) const { return !of.empty() && of[b] >= 0; }
};

}  // namespace vdec
