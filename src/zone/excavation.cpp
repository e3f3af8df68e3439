#include "zone/excavation.hpp"

#include <map>
#include <sstream>

#include "core/errors.hpp"
#include "zone/cst.hpp"

namespace vdec {

ZoneExcavation excavateZones(Model& m, const std::function<bool(Vec2)>& inside, const std::string& where) {
  Zones& zn = m.zones;
  Gridpoints& g = m.gridpoints;
  ZoneExcavation done;
  done.newIndex.assign(zn.size(), -1);
  std::vector<char> onOutline(g.size(), 0);
  for (int v = 0; v < m.vertices.size(); ++v)
    if (m.vertices.gridpoint[v] >= 0) onOutline[m.vertices.gridpoint[v]] = 1;
  Zones kept;
  for (int z = 0; z < zn.size(); ++z) {
    const auto& n = zn.gridpoint[z];
    const Vec2 p0 = g.position[n[0]], p1 = g.position[n[1]], p2 = g.position[n[2]];
    if (!inside((1.0 / 3.0) * (p0 + p1 + p2))) {
      done.newIndex[z] = kept.size();
      kept.gridpoint.push_back(n);
      kept.block.push_back(zn.block[z]);
      kept.material.push_back(zn.material[z]);
      kept.sxx.push_back(zn.sxx[z]);
      kept.syy.push_back(zn.syy[z]);
      kept.sxy.push_back(zn.sxy[z]);
      kept.szz.push_back(zn.szz[z]);
      kept.plasticState.push_back(zn.plasticState[z]);
      continue;
    }
    for (const int i : n)
      if (onOutline[i]) {
        std::ostringstream s;
        s << where << " removes a zone of block '" << m.blocks.name[zn.block[z]] << "' at the block's outline (gridpoint at ("
          << g.position[i].x << ", " << g.position[i].y << ")), where it touches other blocks through contacts; a phase "
          << "excavates zones inside a block that touches others, or any zone of a block alone: excavate at the outline "
          << "before the run with [[excavation]]";
        throw GeometryError(s.str());
      }
    const BlockMaterial& mat = m.blockMaterials[zn.material[z]];
    const double area = 0.5 * cross(p1 - p0, p2 - p0);
    done.strainEnergy += area * elasticEnergyDensity(zn.sxx[z], zn.syy[z], zn.sxy[z], zn.szz[z], mat.bulk, mat.shear);
    ++done.removed;
  }
  if (done.removed == 0) return done;
  kept.nodalForce.assign(3 * static_cast<std::size_t>(kept.size()), {});
  zn = std::move(kept);
  std::vector<char> used(g.size(), 0);
  for (const auto& n : zn.gridpoint)
    for (const int i : n) used[i] = 1;
  for (int i = 0; i < g.size(); ++i) {
    if (used[i] || (g.driven[i] & Excavated)) continue;
    if (i < static_cast<int>(g.mass.size())) done.kineticEnergy += 0.5 * g.mass[i] * dot(g.velocity[i], g.velocity[i]);
    g.driven[i] = DriveX | DriveY | Excavated;
    g.velocity[i] = {0.0, 0.0};
  }
  // The outline now runs round the excavation: a side used by one zone only is a boundary edge,
  // directed with its zone on the left (zones are counter-clockwise).
  std::map<std::pair<int, int>, int> uses;
  for (const auto& n : zn.gridpoint)
    for (int c = 0; c < 3; ++c) ++uses[{std::min(n[c], n[(c + 1) % 3]), std::max(n[c], n[(c + 1) % 3])}];
  m.boundaryEdges.clear();
  for (int z = 0; z < zn.size(); ++z)
    for (int c = 0; c < 3; ++c) {
      const int a = zn.gridpoint[z][c], b = zn.gridpoint[z][(c + 1) % 3];
      if (uses[{std::min(a, b), std::max(a, b)}] == 1) m.boundaryEdges.push_back({zn.block[z], a, b});
    }
  prepareZones(m);
  return done;
}

}  // namespace vdec
