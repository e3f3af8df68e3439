#pragma once
// Snapshots of the model for ParaView: one VTK XML unstructured grid (.vtu) per snapshot, and a
// .pvd collection that lists them with their times. Zones are triangles with their stresses,
// rigid blocks are polygons with their velocity and rotation, contacts are vertices at their
// points with their forces; gridpoints carry displacement and velocity.
#include <string>
#include <vector>

#include "core/model.hpp"

namespace vdec {

class VtkSeries {
 public:
  explicit VtkSeries(std::string directory) : directory_(std::move(directory)) {}
  // Writes DIR/snapshot_<cycle>.vtu and rewrites DIR/model.pvd. Throws OutputError.
  void write(const Model& model);

 private:
  std::string directory_;
  std::vector<std::pair<double, std::string>> written_;  // time, file name
};

}  // namespace vdec
