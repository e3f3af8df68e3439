// The beams: their materials per unit thickness, nodes, elements, loads and ties to the rock.
#include <algorithm>
#include <cmath>

#include "core/errors.hpp"
#include "core/shown.hpp"
#include "scene/build_parts.hpp"
#include "structure/beams.hpp"
#include "structure/bolts.hpp"
#include "structure/cables.hpp"

namespace vdec {

int addBeam(Model& m, const BeamDefinition& d) {
  Structures& st = m.structures;
  for (const Beam& other : st.beams)
    if (other.name == d.name) d.origin.fail("name", "beam '" + d.name + "' is defined twice");
  int material = -1;
  for (int i = 0; i < static_cast<int>(st.materials.size()); ++i)
    if (st.materials[i].name == d.material) material = i;
  if (material < 0) d.origin.fail("material", "no [[beam_material]] is named '" + d.material + "'");
  const BeamMaterial& mat = st.materials[material];
  if (d.tied && !(mat.tieNormalStiffness > 0.0 && mat.tieShearStiffness > 0.0))
    d.origin.fail("tied", "beam '" + d.name + "' is tied to the rock, and its material '" + mat.name +
                              "' gives no tie springs: give tie_normal_stiffness and tie_shear_stiffness > 0");
  BeamNodes& nd = st.nodes;
  BeamElements& el = st.elements;
  const int index = static_cast<int>(st.beams.size());
  const int segments = static_cast<int>(d.points.size()) - (d.closed ? 0 : 1);
  if (static_cast<double>(segments) * d.elements + nd.size() > 1e6)
    d.origin.fail("elements", "beam '" + d.name + "' would bring the beams' nodes past 1e6 (" + std::to_string(segments) +
                                  " segments of " + std::to_string(d.elements) + " elements): use fewer elements");
  Beam beam;
  beam.name = d.name;
  beam.material = material;
  beam.firstNode = nd.size();
  beam.firstElement = el.size();
  beam.closed = d.closed;
  beam.tied = d.tied;
  auto addNode = [&](Vec2 at) {
    nd.beam.push_back(index);
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
  for (int k = 0; k < segments; ++k) {
    const Vec2 a = d.points[k], b = d.points[(k + 1) % d.points.size()];
    for (int i = 0; i < d.elements; ++i) addNode(a + (static_cast<double>(i) / d.elements) * (b - a));
  }
  if (!d.closed) addNode(d.points.back());
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
  return index;
}

int beamNamed(const Model& m, const Origin& origin, const std::string& name) {
  const std::vector<Beam>& beams = m.structures.beams;
  for (int i = 0; i < static_cast<int>(beams.size()); ++i)
    if (beams[i].name == name) return i;
  origin.fail("beam", "no [[beam]] is named '" + name + "'");
}

int nearestBeamNode(const Model& m, int beam, Vec2 point) {
  const Beam& b = m.structures.beams[beam];
  const std::vector<Vec2>& at = m.structures.nodes.initialPosition;
  int node = b.firstNode;
  for (int n = b.firstNode; n < b.firstNode + b.nodeCount; ++n)
    if (norm(at[n] - point) < norm(at[node] - point)) node = n;
  return node;
}

PhaseChanges::BeamNodeChange beamNodeChange(const Model& m, const BeamNodeDefinition& d) {
  const Structures& st = m.structures;
  const int beam = beamNamed(m, d.origin, d.beam);
  const Beam& b = st.beams[beam];
  const BeamNodes& nd = st.nodes;
  const int node = nearestBeamNode(m, beam, d.point);
  double longest = 0.0;
  for (int e = b.firstElement; e < b.firstElement + b.elementCount; ++e) longest = std::max(longest, st.elements.restLength[e]);
  if (norm(nd.initialPosition[node] - d.point) > 0.5 * longest)
    d.origin.fail("point", "lies " + shown(norm(nd.initialPosition[node] - d.point)) + " m from the nearest node of beam '" +
                               d.beam + "', more than half its longest element: give a point on the beam");
  return {node, d.force, d.moment, d.fix};
}

void applyBeamNodeChange(Model& m, const PhaseChanges::BeamNodeChange& c) {
  BeamNodes& nd = m.structures.nodes;
  nd.appliedForce[c.node] += c.force;
  nd.appliedMoment[c.node] += c.moment;
  nd.fixed[c.node] |= c.fix;
}

int addCable(Model& m, const CableDefinition& d) {
  Structures& st = m.structures;
  for (const Cable& other : st.cables)
    if (other.name == d.name) d.origin.fail("name", "cable '" + d.name + "' is defined twice");
  int material = -1;
  for (int i = 0; i < static_cast<int>(st.cableMaterials.size()); ++i)
    if (st.cableMaterials[i].name == d.material) material = i;
  if (material < 0) d.origin.fail("material", "no [[cable_material]] is named '" + d.material + "'");
  const CableMaterial& mat = st.cableMaterials[material];
  CableNodes& nd = st.cableNodes;
  CableElements& el = st.cableElements;
  if (static_cast<double>(d.elements) + nd.size() > 1e6)
    d.origin.fail("elements", "cable '" + d.name + "' would bring the cables' nodes past 1e6: use fewer elements");
  const int index = static_cast<int>(st.cables.size());
  Cable cable;
  cable.name = d.name;
  cable.material = material;
  cable.direction = (1.0 / norm(d.to - d.from)) * (d.to - d.from);
  cable.freeLength = d.freeLength;
  cable.pretension = d.pretension / mat.spacing;
  cable.head = d.head;
  cable.firstNode = nd.size();
  cable.firstElement = el.size();
  for (int i = 0; i <= d.elements; ++i) {
    nd.cable.push_back(index);
    nd.position.push_back(d.from + (static_cast<double>(i) / d.elements) * (d.to - d.from));
    for (auto* v : {&nd.displacement, &nd.velocity, &nd.force, &nd.forceScale, &nd.appliedForce, &nd.mass, &nd.length,
                    &nd.slip, &nd.bondForce})
      v->push_back(0.0);
    nd.fixed.push_back(0);
    nd.slipping.push_back(0);
    nd.hold.push_back({});
  }
  cable.nodeCount = d.elements + 1;
  const double length = norm(d.to - d.from) / d.elements;
  for (int i = 0; i < d.elements; ++i) {
    const int a = cable.firstNode + i, b = a + 1;
    el.node.push_back({a, b});
    el.cable.push_back(index);
    el.restLength.push_back(length);
    el.axialForce.push_back(0.0);
    for (const int n : {a, b}) {
      nd.mass[n] += 0.5 * mat.density * mat.area * length;
      nd.length[n] += 0.5 * length;
    }
  }
  cable.elementCount = d.elements;
  st.cables.push_back(cable);
  return index;
}

int addBolt(Model& m, const BoltDefinition& d) {
  Structures& st = m.structures;
  for (const Bolt& other : st.bolts)
    if (other.name == d.name) d.origin.fail("name", "bolt '" + d.name + "' is defined twice");
  Bolt bolt;
  bolt.name = d.name;
  for (int i = 0; i < static_cast<int>(st.boltMaterials.size()); ++i)
    if (st.boltMaterials[i].name == d.material) bolt.material = i;
  if (bolt.material < 0) d.origin.fail("material", "no [[bolt_material]] is named '" + d.material + "'");
  bolt.from = d.from;
  bolt.to = d.to;
  bolt.direction = normalized(d.to - d.from);
  bolt.firstCrossing = st.crossings.size();
  st.bolts.push_back(bolt);
  return static_cast<int>(st.bolts.size()) - 1;
}

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
  for (const BeamDefinition& d : s.beams) {
    const int index = addBeam(m, d);
    try {
      installBeam(m, index, "");
    } catch (const SceneError& e) {
      d.origin.fail("tied", e.what());  // with the table's file and line
    }
  }
  for (const BeamNodeDefinition& d : s.beamNodes) applyBeamNodeChange(m, beamNodeChange(m, d));
  for (const CableMaterialDefinition& d : s.cableMaterials) {
    for (const CableMaterial& other : st.cableMaterials)
      if (other.name == d.material.name) d.origin.fail("name", "cable material '" + d.material.name + "' is defined twice");
    CableMaterial mat = d.material;
    mat.area /= d.spacing;
    mat.bondStiffness /= d.spacing;
    mat.bondStrength /= d.spacing;
    mat.yieldTension /= d.spacing;
    mat.yieldCompression /= d.spacing;
    mat.spacing = d.spacing;
    st.cableMaterials.push_back(mat);
  }
  for (const CableDefinition& d : s.cables) {
    try {
      installCable(m, addCable(m, d), "");
    } catch (const SceneError& e) {
      d.origin.fail("head", e.what());
    }
  }
  for (const CableNodeDefinition& d : s.cableNodes) {
    const int cable = cableNamed(m, d.origin, d.cable);
    const Cable& c = st.cables[cable];
    CableNodes& nd = st.cableNodes;
    const int node = nearestCableNode(m, cable, d.point);
    const double element = st.cableElements.restLength[c.firstElement];
    if (norm(nd.position[node] - d.point) > 0.5 * element)
      d.origin.fail("point", "lies " + shown(norm(nd.position[node] - d.point)) + " m from the nearest node of cable '" +
                                 d.cable + "', more than half an element: give a point on the cable");
    nd.appliedForce[node] += d.force;
    nd.fixed[node] |= d.fix ? 1 : 0;
  }
  for (const BoltMaterialDefinition& d : s.boltMaterials) {
    for (const BoltMaterial& other : st.boltMaterials)
      if (other.name == d.material.name) d.origin.fail("name", "bolt material '" + d.material.name + "' is defined twice");
    BoltMaterial mat = d.material;
    for (double* perMetre : {&mat.axialStiffness, &mat.shearStiffness, &mat.axialStrength, &mat.shearStrength}) *perMetre /= d.spacing;
    st.boltMaterials.push_back(mat);
  }
  for (const BoltDefinition& d : s.bolts) {
    const int index = addBolt(m, d);
    try {
      installBolt(m, index, "");
    } catch (const SceneError& e) {
      d.origin.fail("points", e.what());
    }
  }
}

int nearestCableNode(const Model& m, int cable, Vec2 point) {
  const Cable& c = m.structures.cables[cable];
  const std::vector<Vec2>& at = m.structures.cableNodes.position;
  int node = c.firstNode;
  for (int n = c.firstNode; n < c.firstNode + c.nodeCount; ++n)
    if (norm(at[n] - point) < norm(at[node] - point)) node = n;
  return node;
}

int cableNamed(const Model& m, const Origin& origin, const std::string& name) {
  const std::vector<Cable>& cables = m.structures.cables;
  for (int i = 0; i < static_cast<int>(cables.size()); ++i)
    if (cables[i].name == name) return i;
  origin.fail("cable", "no [[cable]] is named '" + name + "'");
}

}  // namespace vdec
