#include "boundary/initial_wave.hpp"

#include <cmath>

namespace vdec {

namespace {

// The pulse's shape at a point, its centre moved `travel` along the direction.
double envelope(const InitialWave& w, Vec2 p, double travel) {
  const Vec2 r = p - w.centre;
  const Vec2 across{-w.direction.y, w.direction.x};
  const double s = (dot(r, w.direction) - travel) / w.width;
  const double q = std::isfinite(w.frontWidth) ? dot(r, across) / w.frontWidth : 0.0;
  return std::exp(-(s * s + q * q));
}

}  // namespace

void placeInitialWaves(Model& m, double dt) {
  Gridpoints& g = m.gridpoints;
  Zones& zn = m.zones;
  for (const InitialWave& w : m.initialWaves) {
    const Vec2 d = w.direction, across{-d.y, d.x};
    const Vec2 motion = w.shear ? across : d;
    auto speed = [&](const BlockMaterial& mat) {
      return std::sqrt((w.shear ? mat.shear : mat.bulk + 4.0 * mat.shear / 3.0) / mat.density);
    };
    for (int i = 0; i < g.size(); ++i) {
      if (w.block >= 0 && g.block[i] != w.block) continue;
      const BlockMaterial& mat = m.blockMaterials[m.blocks.material[g.block[i]]];
      // Half a step earlier the pulse was c dt / 2 behind.
      const Vec2 v = (w.amplitude * envelope(w, g.initialPosition[i], -0.5 * speed(mat) * dt)) * motion;
      if (!(g.driven[i] & DriveX)) g.velocity[i].x += v.x;
      if (!(g.driven[i] & DriveY)) g.velocity[i].y += v.y;
    }
    for (int z = 0; z < zn.size(); ++z) {
      if (w.block >= 0 && zn.block[z] != w.block) continue;
      const auto& n = zn.gridpoint[z];
      const Vec2 c = (1.0 / 3.0) * (g.initialPosition[n[0]] + g.initialPosition[n[1]] + g.initialPosition[n[2]]);
      const BlockMaterial& mat = m.blockMaterials[zn.material[z]];
      const double lame = mat.bulk - 2.0 * mat.shear / 3.0, strain = -w.amplitude * envelope(w, c, 0.0) / speed(mat);
      if (w.shear) {
        // A wave travelling forward strains as -v / c: gamma along d and d_perp.
        const double tau = mat.shear * strain;
        zn.sxx[z] += 2.0 * tau * d.x * across.x;
        zn.syy[z] += 2.0 * tau * d.y * across.y;
        zn.sxy[z] += tau * (d.x * across.y + d.y * across.x);
      } else {
        zn.sxx[z] += strain * (lame + 2.0 * mat.shear * d.x * d.x);
        zn.syy[z] += strain * (lame + 2.0 * mat.shear * d.y * d.y);
        zn.sxy[z] += strain * 2.0 * mat.shear * d.x * d.y;
        zn.szz[z] += strain * lame;
      }
    }
  }
}

}  // namespace vdec
