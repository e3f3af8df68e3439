#pragma once
// Excavation of zones during a run (a phase's [[phase.excavation]]): the zones whose centroid
// lies in a region go; docs/user-manual/scene-format.md#phase and docs/models/run-phases.md.
#include <functional>
#include <string>
#include <vector>

#include "core/model.hpp"
#include "geometry/polygon.hpp"

namespace vdec {

// A region of the plane: a circle (radius > 0) or a convex polygon.
struct ExcavationRegion {
  std::string where;   // the scene table it came from, for messages
  Vec2 centre;
  double radius = -1.0;
  Polygon polygon;
  bool contains(Vec2 p) const { return radius > 0.0 ? norm(p - centre) < radius : containsPoint(polygon, p); }
};

struct ZoneExcavation {
  int removed = 0;
  std::vector<int> newIndex;       // old zone -> new zone, -1 for an excavated one
  double strainEnergy = 0.0;       // the elastic energy the removed zones held (J/m)
  double kineticEnergy = 0.0;      // of the gridpoints left without a zone, now at rest
};

// Removes the zones whose centroid (at their present positions) `inside` holds, then forms the
// gridpoints' masses, stiffnesses and zone lists again from the zones left, at their present
// shape, and the blocks' boundary edges (the excavation's outline is a free boundary). A
// gridpoint left without a zone is marked Excavated and held at rest. Throws GeometryError when
// a removed zone touches a contact vertex of a block's outline (`where` names the excavation),
// since contacts follow the outline the blocks were set up with.
ZoneExcavation excavateZones(Model& model, const std::function<bool(Vec2)>& inside, const std::string& where);

}  // namespace vdec
