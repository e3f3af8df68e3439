// The [fluid] table, its flow boundaries and the joints' fluid keys, checked against each other.
#include <cmath>

#include "core/shown.hpp"
#include "scene/build_parts.hpp"

namespace vdec {

FlowBoundary flowBoundary(Model& m, const FlowBoundaryDefinition& d, Vec2 gravity) {
  if (!m.flow.present) d.origin.failTable("needs a [fluid] table: the scene has no fluid to hold or feed");
  FlowBoundary b = d.boundary;
  if (!std::isnan(b.waterTable) && norm(gravity) == 0.0)
    d.origin.fail("water_table", "a hydrostatic pressure needs gravity: give [model] gravity, or a pressure");
  if (d.history) {
    m.timeFunctions.push_back(*d.history);
    b.history = static_cast<int>(m.timeFunctions.size()) - 1;
  }
  return b;
}

void addFluid(Model& m, const SceneDefinition& s) {
  for (const JointMaterialDefinition& d : s.jointMaterials) {
    const JointMaterial& j = d.material;
    if (!s.fluid) {
      const char* given = !std::isnan(j.aperture)            ? "aperture"
                          : !std::isnan(j.residualAperture)  ? "residual_aperture"
                          : std::isfinite(j.maxAperture)     ? "max_aperture"
                          : !std::isnan(j.pointPermeability) ? "point_permeability"
                                                             : nullptr;
      if (given) d.origin.fail(given, "is a fluid-flow property, and the scene has no [fluid] table");
      continue;
    }
    if (j.law == JointLaw::PointContact && std::isnan(j.pointPermeability))
      d.origin.fail("point_permeability", "is required with [fluid]: the point-contact law passes fluid at kc dp (1.4-7)");
    // Every law's apertures give the domains their volume; the cubic law's, their conductance.
    if (std::isnan(j.aperture))
      d.origin.fail("aperture", "is required with [fluid]: the hydraulic aperture at zero normal stress, a0 of 1.4-9 (m)");
    if (std::isnan(j.residualAperture))
      d.origin.fail("residual_aperture", "is required with [fluid]: the least hydraulic aperture, however closed the "
                                         "joint (m, > 0 and at most aperture)");
  }
  if (!s.fluid) {
    if (!s.flowBoundaries.empty()) s.flowBoundaries.front().origin.failTable("needs a [fluid] table: the scene has no fluid");
    return;
  }
  FlowState& f = m.flow;
  f.present = true;
  f.on = s.fluid->flowing;
  f.fluid = s.fluid->fluid;
  if (!std::isnan(f.fluid.waterTable) && norm(m.gravity) == 0.0)
    s.fluid->origin.fail("water_table", "a hydrostatic initial pressure needs gravity: give [model] gravity");
  if (f.fluid.minDomainArea == 0.0) {
    // 1e-9 of the mean block's area: far below any joint's volume at its residual aperture in a
    // scene of sense, so that it only keeps a loop of no length from a zero area.
    double total = 0.0;
    int count = 0;
    for (int b = 0; b < m.blocks.size(); ++b) {
      const int first = m.blocks.firstVertex[b], last = first + m.blocks.vertexCount[b];
      double area = 0.0;
      for (int v = first; v < last; ++v)
        area += 0.5 * cross(m.vertices.localPosition[v], m.vertices.localPosition[m.vertices.next[v]]);
      total += std::abs(area);
      ++count;
    }
    f.fluid.minDomainArea = 1e-9 * (count > 0 ? total / count : 1.0);
  }
  for (const FlowBoundaryDefinition& d : s.flowBoundaries) {
    FlowBoundary b = flowBoundary(m, d, m.gravity);
    for (const FlowBoundary& other : f.boundaries)
      if (!b.name.empty() && other.name == b.name) d.origin.fail("name", "flow boundary '" + b.name + "' is defined twice");
    f.boundaries.push_back(b);
  }
}

}  // namespace vdec
