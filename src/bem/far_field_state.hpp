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
  // The interface's nodes in order, counter-clockwise about the blocks; each joins one gridpoint,
  // or the coincident gridpoints of two blocks where the outer boundary crosses a joint.
  std::vector<Vec2> node;              // as installed
  std::vector<int> firstGridpoint;     // node i's gridpoints: gridpoints[firstGridpoint[i] .. firstGridpoint[i + 1])
  std::vector<int> gridpoints;
  std::vector<std::array<int, 2>> edge;  // the interface's edges in order: their two gridpoints (a zone's edge)
  std::vector<double> stiffness;       // K, 2n x 2n, row-major: the region's force on the nodes is f0 - K u
  std::vector<Vec2> initialForce;      // f0: the stress the zones had at installation, held
  std::vector<Vec2> force;             // the region's force on each node, of the last step
  double buildSeconds = 0.0;           // forming K
  int size() const { return static_cast<int>(node.size()); }
};

}  // namespace vdec
