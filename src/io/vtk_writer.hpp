#pragma once
// Snapshots of the model for ParaView: one VTK XML unstructured grid (.vtu) per snapshot, and a
// .pvd collection that lists them with their times. Zones are triangles with their stresses,
// rigid blocks are polygons with their velocity and rotation, contacts are vertices at their
// points with their forces; gridpoints carry displacement and velocity. With [fluid], the
// domains (at their centres, with pressure and area) and the flow knots (at their points, with
// flow and aperture) are vertices too.
#include <string>
#include <vector>

#include "core/model.hpp"

namespace vdec {

class VtkSeries {
 public:
  explicit VtkSeries(std::string directory) : directory_(std::move(directory)) {}
  // Removes model.pvd and snapshot_<cycle>.vtu files an earlier run left in `directory`, so that
  // they cannot pass for this run's. Other files are left alone. Throws OutputError.
  static void removeStale(const std::string& directory);
  // Creates the directory and checks that a file can be written in it, before the run starts.
  // Throws OutputError naming it.
  void prepare() const;
  // Writes DIR/snapshot_<cycle>.vtu and rewrites DIR/model.pvd, each under a temporary name
  // renamed over the target (io/atomic_file.hpp). Throws OutputError.
  void write(const Model& model);

 private:
  std::string directory_;
  std::vector<std::pair<double, std::string>> written_;  // time, file name
};

}  // namespace vdec
