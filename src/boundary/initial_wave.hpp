#pragma once
// Plane P and S waves in the model at the start ([[initial_wave]]): a dynamic input that no
// boundary gives, for waves that meet a boundary at an angle. docs/models/boundaries.md#derivation.
#include "core/model.hpp"

namespace vdec {

// Adds each initial wave's field to the deformable blocks it covers: a pulse
// u = A g(s - c t) along the direction d (P) or across it (S), g Gaussian in s = (x - x0) . d of
// half-width `width` and, along the front, in (x - x0) . d_perp of half-width `frontWidth`. The
// zones get its stress at t = 0 at their centroids (P: -(A g / C_p)(lambda I + 2 G d d); S:
// -(A g / C_s) G (d d_perp + d_perp d)), the free components of the gridpoints its particle
// velocity at t = -dt/2, where the central-difference scheme starts its velocities.
void placeInitialWaves(Model& model, double dt);

}  // namespace vdec
