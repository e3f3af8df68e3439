#pragma once
// Simply-deformable blocks (NUREG/CR-5429 1.3.3.3; docs/models/simply-deformable.md): the three
// modes of uniform strain a block adds to its rigid motion, their elastic stress, generalised
// forces and masses, and their step in the explicit scheme.
#include "contact/strained_outline.hpp"
#include "core/model.hpp"
#include "geometry/polygon.hpp"
#include "motion/motion_totals.hpp"

namespace vdec {

// Makes rigid block b simply deformable (its vertices' local positions are its polygon about
// the centroid): its consistent mass of rotation and strain, from its material's density.
void addStrainModes(Model& model, int block);

// sigma = D E of block b's present strain (plane strain, tension positive), in its frame; szz
// its out-of-plane stress.
Sym2 presentStress(const Model& model, int block, double& szz);
// sigma = D E of every simply-deformable block (plane strain); returns their elastic energy,
// A sigma : E / 2 (J/m).
double strainModeStress(Model& model);

// Advances block b's rotation and strains by one step (1.3-21 with the consistent mass), given
// its moment and body moment; accumulates the totals, its unbalanced force the norm of its
// translation's (the sum of squares given) and its generalised loads over its reach. The
// rigid-block stage calls it in place of the rotation's own advance.
void advanceStrainModes(Model& model, int block, double dt, double massDamping, double localDamping,
                        double bodyMoment, double translationUnbalanced, MotionStepTotals& totals);

// A tensor of block b's frame in the world's axes, R t R^T.
Sym2 inWorldAxes(const Model& model, int block, const Sym2& t);
// The kinetic energy of block b's strain modes beyond the rigid rotation's I omega^2 / 2: the
// strain rates' own and their coupling to the rotation.
double strainModeKineticEnergy(const Model& model, int block);
// I omega^2 / 2 + omega M_rotation,strain dE/dt: what the kinetic energy of block b's free modes
// loses when its rotation becomes driven (held at its velocity).
double rotationKineticEnergy(const Model& model, int block);
// The energy of block b's strain modes, elastic and kinetic beyond the rigid rotation's, set to
// zero: what an excavation takes out of the model with the block. Call it before the block's
// angular velocity is zeroed.
double releaseStrainModes(Model& model, int block);
// Sets block b's strain rates to zero; returns the kinetic energy that takes away.
double stopStrainRates(Model& model, int block);
// After block b's local frame has turned by its rotation (its local positions turned by c, s, its
// rotation about to become zero): its strain, strain rate and stress in the new frame, and its
// mass formed again from the turned shape.
void turnStrainFrame(Model& model, int block);

// The step at which the stiffest mode of rotation and strain of any simply-deformable block is
// stable: frac * 2 / sqrt(lambda_max(M^-1 K)), K its elastic stiffness and, at every vertex, a
// contact spring max(kn, ks) times its longest edge (as 1.3-28 takes for translation); infinity
// without such blocks.
double strainModeTimeStep(const Model& model, double frac);

}  // namespace vdec
