// The beams: their materials per unit thickness, nodes, elements, loads and ties to the rock.
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/shown.hpp"
#include "geometry/polygon.hpp"
#include "scene/build_parts.hpp"

namespace vdec {

namespace {

double segmentDistance(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 d = b - a;
  const double t = std::clamp(dot(p - a, d) / dot(d, d), 0.0, 1.0);
  return norm(p - (a + t * d));
}

// Distance from a point to a triangle (0 inside) and the point's barycentric weights, clamped
// to the triangle.
double triangleDistance(Vec2 p, const std::array<Vec2, 3>& v, std::array<double, 3>& weight) {
  const double area = cross(v[1] - v[0], v[2] - v[0]);
  for (int k = 0; k < 3; ++k) weight[k] = cross(v[(k + 1) % 3] - p, v[(k + 2) % 3] - p) / area;
  if (weight[0] >= 0.0 && weight[1] >= 0.0 && weight[2] >= 0.0) return 0.0;
  double best = INFINITY;
  for (int k = 0; k < 3; ++k) best = std::min(best, segmentDistance(p, v[k], v[(k + 1) % 3]));
  double sum = 0.0;
  for (double& w : weight) sum += (w = std::max(w, 0.0));
  for (double& w : weight) w /= sum;
  return best;
}

// The rock a node is tied to: the zone (deformable block) or the block holding its point, else
// the nearest within the rounding length (a lining on an excavated face lies on the blocks' edge).
BeamTie tieFor(const Model& m, const BeamDefinition& d, Vec2 point) {
  BeamTie best;
  double nearest = INFINITY;
  for (int b = 0; b < m.blocks.size(); ++b) {
    if (m.blocks.deformable[b]) continue;
    Polygon p;
    const int first = m.blocks.firstVertex[b], last = first + m.blocks.vertexCount[b];
    for (int v = first; v < last; ++v) p.push_back(m.vertices.geometry[v].position);
    double distance = containsPoint(p, point) ? 0.0 : INFINITY;
    for (int v = 0; distance > 0.0 && v < static_cast<int>(p.size()); ++v)
      distance = std::min(distance, segmentDistance(point, p[v], p[(v + 1) % p.size()]));
    if (distance < nearest) {
      nearest = distance;
      best = {};
      best.block = b;
      best.local = point - m.blocks.centroid[b];
    }
  }
  for (int z = 0; z < m.zones.size(); ++z) {
    std::array<Vec2, 3> corner;
    for (int k = 0; k < 3; ++k) corner[k] = m.gridpoints.position[m.zones.gridpoint[z][k]];
    std::array<double, 3> weight;
    const double distance = triangleDistance(point, corner, weight);
    if (distance < nearest) {
      nearest = distance;
      best = {};
      best.block = m.zones.block[z];
      best.zone = z;
      best.weight = weight;
    }
  }
  if (!(nearest <= m.roundingLength))
    d.origin.fail("tied", "beam '" + d.name + "': its node at (" + shown(point.x) + ", " + shown(point.y) +
                              ") lies on no block (the nearest is " + shown(nearest) + " m away, beyond the rounding "
                              "length): place the beam on the rock, or set tied = false");
  return best;
}

}  // namespace

void addStructures(Model& m, const SceneDefinition& s) {
  Structures& st = m.structures;
  for (const BeamMaterialDefinition& d : s.beamMaterials) {
    for (const BeamMaterial& other : st.materials)
      if (other.name == d.material.name) d.origin.fail("name", "beam material '" + d.material.name + "' is defined twice");
    BeamMaterial mat = d.material;
    mat.area /= d.spacing;
    mat.inertia /= d.spacing;
    st.materials.push_back(mat);
  }
  BeamNodes& nd = st.nodes;
  BeamElements& el = st.elements;
  auto addNode = [&](int beam, Vec2 at) {
    nd.beam.push_back(beam);
    nd.initialPosition.push_back(at);
    nd.position.push_back(at);
    nd.rotation.push_back(0.0);
    nd.velocity.push_back({});
    nd.angularVelocity.push_back(0.0);
    nd.force.push_back({});
    nd.moment.push_back(0.0);
    nd.tieForce.push_back({});
    nd.forceScale.push_back(0.0);
    nd.appliedForce.push_back({});
    nd.appliedMoment.push_back(0.0);
    nd.mass.push_back(0.0);
    nd.rotaryInertia.push_back(0.0);
    nd.length.push_back(0.0);
    nd.fixed.push_back(0);
  };
  for (const BeamDefinition& d : s.beams) {
    for (const Beam& other : st.beams)
      if (other.name == d.name) d.origin.fail("name", "beam '" + d.name + "' is defined twice");
    int material = -1;
    for (int i = 0; i < static_cast<int>(st.materials.size()); ++i)
      if (st.materials[i].name == d.material) material = i;
    if (material < 0) d.origin.fail("material", "no [[beam_material]] is named '" + d.material + "'");
    const BeamMaterial& mat = st.materials[material];
    Beam beam{d.name, material, nd.size(), 0, el.size(), 0, d.closed};
    const int index = static_cast<int>(st.beams.size());
    const int segments = static_cast<int>(d.points.size()) - (d.closed ? 0 : 1);
    if (static_cast<double>(segments) * d.elements + nd.size() > 1e6)
      d.origin.fail("elements", "beam '" + d.name + "' would bring the beams' nodes past 1e6 (" +
                                    std::to_string(segments) + " segments of " + std::to_string(d.elements) +
                                    " elements): use fewer elements");
    for (int k = 0; k < segments; ++k) {
      const Vec2 a = d.points[k], b = d.points[(k + 1) % d.points.size()];
      for (int i = 0; i < d.elements; ++i) addNode(index, a + (static_cast<double>(i) / d.elements) * (b - a));
    }
    if (!d.closed) addNode(index, d.points.back());
    beam.nodeCount = nd.size() - beam.firstNode;
    const int elements = d.closed ? beam.nodeCount : beam.nodeCount - 1;
    for (int i = 0; i < elements; ++i) {
      const int a = beam.firstNode + i, b = beam.firstNode + (i + 1) % beam.nodeCount;
      const Vec2 chord = nd.position[b] - nd.position[a];
      const double length = norm(chord);
      el.node.push_back({a, b});
      el.beam.push_back(index);
      el.restLength.push_back(length);
      el.restAngle.push_back(std::atan2(chord.y, chord.x));
      el.axialForce.push_back(0.0);
      el.shearForce.push_back(0.0);
      el.endMoment.push_back({0.0, 0.0});
      // Lumped: each node takes half the element's mass, and as rotary inertia that half's about
      // the node as a rod, (rho A L / 2) (L / 2)^2 / 3 (the section's own rho I is far smaller and
      // would shorten the step for nothing a static or low-frequency answer needs).
      const double half = 0.5 * mat.density * mat.area * length;
      for (const int n : {a, b}) {
        nd.mass[n] += half;
        nd.rotaryInertia[n] += half * length * length / 12.0;
        nd.length[n] += 0.5 * length;
        nd.appliedForce[n] += (0.5 * length) * d.load;
      }
    }
    beam.elementCount = el.size() - beam.firstElement;
    st.beams.push_back(beam);
    if (!d.tied) continue;
    if (!(mat.tieNormalStiffness > 0.0 && mat.tieShearStiffness > 0.0))
      d.origin.fail("tied", "beam '" + d.name + "' is tied to the rock, and its material '" + mat.name +
                                "' gives no tie springs: give tie_normal_stiffness and tie_shear_stiffness > 0");
    for (int n = beam.firstNode; n < beam.firstNode + beam.nodeCount; ++n) {
      BeamTie t = tieFor(m, d, nd.position[n]);
      t.node = n;
      t.normalStiffness = mat.tieNormalStiffness * nd.length[n];
      t.shearStiffness = mat.tieShearStiffness * nd.length[n];
      t.cohesion = mat.tieCohesion * nd.length[n];
      t.friction = mat.tieFriction;
      t.tension = mat.tieTension * nd.length[n];
      st.ties.push_back(t);
    }
  }
  for (const BeamNodeDefinition& d : s.beamNodes) {
    int beam = -1;
    for (int i = 0; i < static_cast<int>(st.beams.size()); ++i)
      if (st.beams[i].name == d.beam) beam = i;
    if (beam < 0) d.origin.fail("beam", "no [[beam]] is named '" + d.beam + "'");
    const Beam& b = st.beams[beam];
    int node = b.firstNode;
    for (int n = b.firstNode; n < b.firstNode + b.nodeCount; ++n)
      if (norm(nd.position[n] - d.point) < norm(nd.position[node] - d.point)) node = n;
    double longest = 0.0;
    for (int e = b.firstElement; e < b.firstElement + b.elementCount; ++e) longest = std::max(longest, el.restLength[e]);
    if (norm(nd.position[node] - d.point) > 0.5 * longest)
      d.origin.fail("point", "lies " + shown(norm(nd.position[node] - d.point)) + " m from the nearest node of beam '" +
                                 d.beam + "', more than half its longest element: give a point on the beam");
    nd.appliedForce[node] += d.force;
    nd.appliedMoment[node] += d.moment;
    nd.fixed[node] |= d.fix;
  }
  if (!st.ties.empty()) {
    m.blocks.boundaryForce.resize(m.blocks.size());
    m.blocks.boundaryMoment.resize(m.blocks.size());
  }
}

}  // namespace vdec
