#pragma once
// A boundary-element far field (NUREG/CR-5429 1.4.5): the elastic plane or half-plane outside the
// block model's outer boundary, condensed into a dense stiffness on the interface's nodes. Plain
// arrays, part of the Model; bem/far_field.hpp applies it.
#include <array>
#include <vector>

#include "core/vec2.hpp"

namespace vdec {

struct BoundaryElementField {
  bool on = false;
  double young = 0.0, poisson = 0.0;   // of the region, plane strain
  bool halfPlane = false;
  double surfaceY = 0.0;               // the half-plane's free surface (the region below it)
  bool closed = true;                  // the interface a closed loop (plane) or a chain (half-plane)
  // The interface's nodes in order, counter-clockwise about the blocks; each joins one point of a
  // block, or the coincident points of two blocks where the outer boundary crosses a joint. A
  // point is a deformable block's gridpoint or a rigid block's vertex (the other index -1).
  std::vector<Vec2> node;              // as installed: the weighted mean of its points
  std::vector<int> firstMember;        // node i's points: members firstMember[i] .. firstMember[i + 1] - 1
  std::vector<int> memberGridpoint;
  std::vector<int> memberVertex;
  // A point's weight in its node: its share of the node's tributary length (half of each
  // interface edge of its block that ends there). A node moves by the weighted mean of its points
  // and the region's response to that motion is shared in the same proportions (the coupling stays
  // symmetric), so that at a joint each block takes the load of its own edges.
  std::vector<double> memberWeight;
  // The interface's edges in order (edge k from node k to node k + 1): their two gridpoints (a
  // zone's edge), or -1 for a rigid block's edge, which holds the in-situ stress below; and the
  // members at its two ends, which carry its share of f0.
  std::vector<std::array<int, 2>> edge;
  std::vector<std::array<int, 2>> edgeMember;
  // [initial_stress]'s sxx, syy, sxy at the origin and their gradients in x and y: a rigid block
  // has no stress of its own, so its edges hold this when the region is put in place.
  std::array<double, 3> inSitu{}, inSituGradientX{}, inSituGradientY{};
  std::vector<double> stiffness;       // K, 2n x 2n, row-major: the region's force on the nodes is f0 - K u
  std::vector<Vec2> memberInitialForce;  // f0 on each point: half of each of its edges' sigma n at installation, held
  std::vector<Vec2> force;             // the region's force on each node, of the last step
  double buildSeconds = 0.0;           // forming K
  int size() const { return static_cast<int>(node.size()); }
};

}  // namespace vdec
