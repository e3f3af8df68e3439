#pragma once
// Contact detection: a uniform-grid broad phase over block bounding boxes, then the rounded-
// corner narrow phase for each candidate pair. Detection runs only when blocks may have moved
// far enough to make or break a contact: when some vertex has moved more than half the contact
// tolerance from where the last scan saw it, since until then no pair can have closed a gap
// larger than the tolerance.
#include <vector>

#include "contact/broad_phase.hpp"
#include "contact/contact_geometry.hpp"
#include "core/model.hpp"

namespace vdec {

class ContactDetection {
 public:
  // First detection. Contacts found here are "initial": bonded joints keep their tensile
  // strength and cohesion. Throws GeometryError naming the blocks if any overlap at the start.
  void initialise(Model& model);
  // Called once per step with the largest vertex displacement of that step.
  void update(Model& model, double largestStepDisplacement);
  // Stops the run (InstabilityError) when, in the step just taken, two blocks within reach of
  // each other moved more than a quarter of the rounding length relative to each other: then a
  // corner could have crossed a face, or a thin block, between two scans or two evaluations
  // without any overlap ever being seen. Cheap unless some vertex moved that far.
  void checkStepReach(const Model& model, double dt, double largestStepDisplacement);
  // Blocks to rescan at the next update whatever their motion.
  void requestRescan(const std::vector<int>& blocks) { requested_.insert(requested_.end(), blocks.begin(), blocks.end()); }
  // Rescans `blocks` now, not at the next update: the contacts of an excavated block go at once.
  void rescanNow(Model& model, const std::vector<int>& blocks);
  int scans() const { return scans_; }
  // What carries from one step to the next (core/state_archive.hpp); the rest are scratch buffers.
  template <class A>
  void visitState(A& a) {
    a(motionSinceScan_), a(margin_), a(displacement_), a(moved_), a(requested_), a(scanCentroid_);
    a(scanRotation_), a(scanGridpoint_), a(scans_);
  }

 private:
  // All blocks (moved == nullptr), or those flagged in moved and the contacts they take part in.
  void scan(Model& model, const std::vector<char>* moved = nullptr);
  std::vector<std::pair<int, int>> candidatePairs(const Model& model);
  // Each block's bounding box, grown by half the contact tolerance, into minX_ .. maxY_.
  void measureBoxes(const Model& model);
  void measureDisplacements(const Model& model);

  double motionSinceScan_ = 0.0;  // path of the fastest vertex since the last measure
  double margin_ = 0.0;           // how far it may go before a block could need a rescan
  std::vector<double> displacement_;  // per block, from its last scan
  std::vector<char> moved_;
  std::vector<int> requested_;
  std::vector<Vec2> scanCentroid_;  // block and gridpoint positions at each block's last scan
  std::vector<double> scanRotation_;
  std::vector<Vec2> scanGridpoint_;
  int scans_ = 0;
  BroadPhaseGrid grid_;
  struct Candidate {
    int corner, blockA, blockB;
    FeatureHit hit;
    const Contact* existing;  // the contact with this key before the scan, if any
  };
  std::vector<Candidate> found_;        // buffers reused from scan to scan
  std::vector<Contact> spareContacts_;
  std::vector<YieldingState> spareStates_;
  std::vector<Contact> mergedContacts_;
  std::vector<int> origin_, mergedOrigin_;
  std::vector<double> minX_, maxX_, minY_, maxY_;
  std::vector<Vec2> translation_;  // checkStepReach's per-block motion of the step
  std::vector<double> spread_;
};

}  // namespace vdec
