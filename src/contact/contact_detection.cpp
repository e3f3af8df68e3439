#include "contact/contact_detection.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "contact/broad_phase.hpp"
#include "contact/contact_geometry.hpp"
#include "core/errors.hpp"
#include "joint/joint_laws.hpp"

namespace vdec {

namespace {

// A per-contact side array follows the contacts through a scan: entry k of the new list is the
// previous entry origin[k], or fresh(contact k) for a contact the scan made. One permutation
// serves every such array (the continuously-yielding state today).
template <class T, class Fresh>
void carryContactArray(std::vector<T>& array, const std::vector<int>& origin, std::vector<T>& spare, Fresh fresh,
                       const std::vector<Contact>& contacts) {
  spare.clear();
  spare.reserve(origin.size());
  for (std::size_t k = 0; k < origin.size(); ++k) spare.push_back(origin[k] >= 0 ? array[origin[k]] : fresh(contacts[k]));
  std::swap(array, spare);
}

struct Key {
  int corner, blockB;
  bool operator<(const Key& o) const { return corner != o.corner ? corner < o.corner : blockB < o.blockB; }
  bool operator==(const Key& o) const { return corner == o.corner && blockB == o.blockB; }
};

}  // namespace

void ContactDetection::measureBoxes(const Model& m) {
  const int n = m.blocks.size();
  const double inflate = 0.5 * m.contactTolerance;
  minX_.assign(n, INFINITY);
  maxX_.assign(n, -INFINITY);
  minY_.assign(n, INFINITY);
  maxY_.assign(n, -INFINITY);
  auto extend = [&](int b, Vec2 p) {
    minX_[b] = std::min(minX_[b], p.x - inflate);
    maxX_[b] = std::max(maxX_[b], p.x + inflate);
    minY_[b] = std::min(minY_[b], p.y - inflate);
    maxY_[b] = std::max(maxY_[b], p.y + inflate);
  };
  for (int v = 0; v < m.vertices.size(); ++v) extend(m.vertices.block[v], m.vertices.geometry[v].position);
}

std::vector<std::pair<int, int>> ContactDetection::candidatePairs(const Model& m) {
  measureBoxes(m);
  std::vector<std::pair<int, int>> pairs = overlappingPairs(minX_, maxX_, minY_, maxY_, grid_);
  // An excavated block touches nothing: its contacts go at the scan after the excavation.
  const Blocks& b = m.blocks;
  pairs.erase(std::remove_if(pairs.begin(), pairs.end(),
                             [&b](const auto& p) { return b.excavated(p.first) || b.excavated(p.second); }),
              pairs.end());
  return pairs;
}

void ContactDetection::scan(Model& m, const std::vector<char>* moved) {
  ++scans_;
  const int n = m.blocks.size();
  auto rescanned = [moved](int b) { return moved == nullptr || (*moved)[b] != 0; };
  // The rescanned blocks' positions become the reference their later motion is measured from.
  scanCentroid_.resize(n);
  scanRotation_.resize(n);
  scanGridpoint_.resize(m.gridpoints.size());
  for (int b = 0; b < n; ++b) {
    if (!rescanned(b)) continue;
    scanCentroid_[b] = m.blocks.centroid[b];
    scanRotation_[b] = m.blocks.rotation[b];
  }
  for (int i = 0; i < m.gridpoints.size(); ++i)
    if (rescanned(m.gridpoints.block[i])) scanGridpoint_[i] = m.gridpoints.position[i];
  // Contacts persist by key (corner, block B); the previous list is looked up through a sorted
  // index so that the contacts themselves are not moved.
  const std::vector<Contact>& previous = m.contacts;
  std::vector<std::pair<Key, int>> previousIndex(previous.size());
  for (std::size_t i = 0; i < previous.size(); ++i)
    previousIndex[i] = {Key{previous[i].corner, previous[i].blockB}, static_cast<int>(i)};
  // In order already unless a contact was handed over to the other corner since the last scan.
  // A hand-over can also make a contact with the key of one the scan made since; of two such,
  // the closed one, then the earlier in the list, is the one carried on, the other dropped.
  auto byKeyThenClosed = [&previous](const auto& a, const auto& b) {
    if (a.first < b.first || b.first < a.first) return a.first < b.first;
    if (previous[a.second].open != previous[b.second].open) return !previous[a.second].open;
    return a.second < b.second;
  };
  if (!std::is_sorted(previousIndex.begin(), previousIndex.end(), byKeyThenClosed))
    std::sort(previousIndex.begin(), previousIndex.end(), byKeyThenClosed);
  // Candidates come in ascending key order, so the previous contact with the same key is found
  // by walking forward through the sorted index.
  std::size_t walk = 0;
  auto findPrevious = [&](int corner, int blockB) -> const Contact* {
    const Key k{corner, blockB};
    while (walk < previousIndex.size() && previousIndex[walk].first < k) ++walk;
    return (walk < previousIndex.size() && previousIndex[walk].first == k) ? &previous[previousIndex[walk].second]
                                                                            : nullptr;
  };

  // Neighbours per block, ascending, so that walking blocks, their corners and then their
  // neighbours produces candidates already in key order (corner, block B). A partial scan
  // looks only at the pairs with a rescanned block; the others keep their contacts as they are.
  auto pairs = candidatePairs(m);
  if (moved != nullptr)
    pairs.erase(std::remove_if(pairs.begin(), pairs.end(), [&](const auto& p) { return !rescanned(p.first) && !rescanned(p.second); }),
                pairs.end());
  std::vector<int> neighbourStart(n + 1, 0), neighbours(2 * pairs.size());
  for (const auto& [a, b] : pairs) {
    ++neighbourStart[a + 1];
    ++neighbourStart[b + 1];
  }
  for (int b = 0; b < n; ++b) neighbourStart[b + 1] += neighbourStart[b];
  {
    std::vector<int> fill(neighbourStart.begin(), neighbourStart.end() - 1);
    for (const auto& [a, b] : pairs) {
      neighbours[fill[a]++] = b;
      neighbours[fill[b]++] = a;
    }
    // Ascending, whatever order the broad phase found the pairs in.
    for (int b = 0; b < n; ++b) std::sort(neighbours.begin() + neighbourStart[b], neighbours.begin() + neighbourStart[b + 1]);
  }
  // The scan's big lists reuse the buffers of the previous scan: fresh ones, megabytes for a
  // large model, would be faulted in page by page every time.
  std::vector<Candidate>& found = found_;
  found.clear();
  // A corner within the tolerance of B has its vertex within tolerance + d of B's polygon (the
  // rounded tip lies less than d inside the vertex): a box test rejects the others cheaply.
  const double reach = m.contactTolerance + m.roundingLength - 0.5 * m.contactTolerance;
  for (int a = 0; a < n; ++a) {
    const int first = m.blocks.firstVertex[a], last = first + m.blocks.vertexCount[a];
    for (int v = first; v < last; ++v) {
      const Vec2 p = m.vertices.geometry[v].position;
      for (int k = neighbourStart[a]; k < neighbourStart[a + 1]; ++k) {
        const int b = neighbours[k];
        if (p.x < minX_[b] - reach || p.x > maxX_[b] + reach || p.y < minY_[b] - reach || p.y > maxY_[b] + reach)
          continue;
        // A contact that exists already is followed from its feature, as the contact stage
        // follows it every step; only a new candidate needs the search over all of B's features.
        const Contact* existing = findPrevious(v, b);
        const FeatureHit hit = existing ? followFeature(m, v, b, existing->feature, existing->featureKind)
                                        : nearestFeature(m, v, b);
        if (hit.overlap >= -m.contactTolerance) found.push_back({v, a, b, hit, existing});
      }
    }
  }
  // The candidates of each vertex are contiguous (found is in key order): index them by vertex.
  std::vector<int> firstOfVertex(m.vertices.size() + 1, 0);
  for (const Candidate& f : found) ++firstOfVertex[f.corner + 1];
  for (int v = 0; v < m.vertices.size(); ++v) firstOfVertex[v + 1] += firstOfVertex[v];
  auto findFound = [&](int corner, int blockB) -> const Candidate* {
    for (int i = firstOfVertex[corner]; i < firstOfVertex[corner + 1]; ++i)
      if (found[i].blockB == blockB) return &found[i];
    return nullptr;
  };

  // Two corners at one spot can each see the other: keep one contact for the pair. A corner
  // that sees the other corner yields to that corner's contact on this block when the other
  // corner sees an edge (it is the one pressed into a face) or another corner. Of two mutual
  // corner-corner contacts the one that already exists stays, so that its state is kept; of two
  // new ones, the one owned by the lower vertex id.
  const bool initial = m.cycle == 0;
  const double touching = 1e-6 * m.roundingLength;
  std::vector<Contact> kept = std::move(spareContacts_);
  kept.clear();
  kept.reserve(found.size());
  // Where each kept contact came from in the previous list (-1: new), for the per-contact side
  // arrays, which follow the contacts through this one permutation.
  std::vector<int>& origin = origin_;
  origin.clear();
  origin.reserve(found.size());
  for (const Candidate& f : found) {
    if (f.hit.kind == FeatureKind::Corner) {
      if (const Candidate* reverse = findFound(f.hit.feature, f.blockA)) {
        const bool mutual = reverse->hit.kind == FeatureKind::Corner && reverse->hit.feature == f.corner;
        if (!mutual) continue;
        const bool existed = f.existing != nullptr, reverseExisted = reverse->existing != nullptr;
        if (existed != reverseExisted ? reverseExisted : reverse->corner < f.corner) continue;
      }
    }
    // Carry the state of a contact that persists.
    if (const Contact* old = f.existing) {
      kept.push_back(*old);
      origin.push_back(static_cast<int>(old - previous.data()));
      continue;
    }
    // A new contact. A joint contact's stress is its spring's from zero overlap: stress-free
    // where the faces touch, the stress of the face around it where it appears under load,
    // open where found at a gap.
    Contact c;
    c.corner = f.corner;
    c.blockA = f.blockA;
    c.blockB = f.blockB;
    c.feature = f.hit.feature;
    c.featureKind = f.hit.kind;
    c.overlap = f.hit.overlap;
    c.joint = m.jointMaterialFor(c.blockA, c.blockB);
    const JointMaterial& j = m.jointMaterials[c.joint];
    c.length = contactLength(m, c.corner, f.hit, m.blocks.deformable[c.blockA] || m.blocks.deformable[c.blockB]);
    c.elasticNormalStress = j.law == JointLaw::ContinuouslyYielding ? cyNormalStressOfClosure(j, c.overlap)
                                                                     : j.kn * c.overlap;
    c.open = c.overlap < 0.0;
    // Model #5: only contacts present at the start are bonded rock; faces that come together
    // later have no cohesion or tensile strength.
    c.intact = initial || j.law != JointLaw::CoulombFracture;
    if (initial && c.overlap > touching) {
      std::ostringstream s;
      s << "blocks '" << m.blocks.name[c.blockA] << "' and '" << m.blocks.name[c.blockB]
        << "' overlap at the start (corner " << c.corner - m.blocks.firstVertex[c.blockA] << " of '"
        << m.blocks.name[c.blockA] << "' is " << c.overlap << " m inside); move them apart so they at most touch";
      throw GeometryError(s.str());
    }
    if (initial && c.overlap >= -touching) {
      c.elasticNormalStress = 0.0;  // faces touching at the start: closed and stress-free
      c.open = false;
    }
    c.springEnergy = c.open ? 0.0 : contactWeight(j, c) * jointSpringEnergy(j, c);
    kept.push_back(c);
    origin.push_back(-1);
  }
  if (moved != nullptr) {
    // The contacts between blocks neither of which was rescanned stay as they were. Both lists
    // are in key order; merged, the result is too.
    std::vector<Contact>& merged = mergedContacts_;
    std::vector<int>& mergedOrigin = mergedOrigin_;
    merged.clear();
    mergedOrigin.clear();
    std::size_t k = 0;
    auto takeKept = [&] {
      merged.push_back(kept[k]);
      mergedOrigin.push_back(origin[k]);
      ++k;
    };
    Key last{-1, -1};  // a key met twice (see byKeyThenClosed) is carried once
    for (const auto& [key, index] : previousIndex) {
      const Contact& old = previous[index];
      if (rescanned(old.blockA) || rescanned(old.blockB) || key == last) continue;
      last = key;
      while (k < kept.size() && Key{kept[k].corner, kept[k].blockB} < key) takeKept();
      merged.push_back(old);
      mergedOrigin.push_back(index);
    }
    while (k < kept.size()) takeKept();
    std::swap(kept, merged);
    std::swap(origin, mergedOrigin);
  }
  spareContacts_ = std::move(m.contacts);
  m.contacts = std::move(kept);
  if (m.hasYieldingJoints())
    carryContactArray(m.yieldingStates, origin, spareStates_,
                      [&m](const Contact& c) { return YieldingState{m.jointMaterials[c.joint].initialFriction}; }, m.contacts);
}

namespace {

// Whether an edge of block a crosses an edge of block b: each edge's end points lie strictly on
// opposite sides of the other's line, by more than `touching`. Faces that touch, corners on
// faces and corners on corners are not crossings. Two blocks laid across each other like a plus
// sign overlap without a corner of either inside the other; this is what finds them.
bool edgesCross(const Model& m, int a, int b, double touching) {
  const Vertices& vx = m.vertices;
  auto side = [&](int edge, Vec2 p) { return cross(vx.geometry[edge].edgeDirection, p - vx.geometry[edge].position); };
  const int firstA = m.blocks.firstVertex[a], lastA = firstA + m.blocks.vertexCount[a];
  const int firstB = m.blocks.firstVertex[b], lastB = firstB + m.blocks.vertexCount[b];
  for (int i = firstA; i < lastA; ++i) {
    for (int j = firstB; j < lastB; ++j) {
      const double b0 = side(i, vx.geometry[j].position), b1 = side(i, vx.geometry[vx.next[j]].position);
      if (!((b0 > touching && b1 < -touching) || (b0 < -touching && b1 > touching))) continue;
      const double a0 = side(j, vx.geometry[i].position), a1 = side(j, vx.geometry[vx.next[i]].position);
      if ((a0 > touching && a1 < -touching) || (a0 < -touching && a1 > touching)) return true;
    }
  }
  return false;
}

}  // namespace

void ContactDetection::initialise(Model& m) {
  scan(m);
  motionSinceScan_ = 0.0;
  margin_ = 0.45 * m.contactTolerance;
  const double touching = 1e-6 * m.roundingLength;
  for (const auto& [a, b] : candidatePairs(m)) {
    if (!edgesCross(m, a, b, touching)) continue;
    throw GeometryError("blocks '" + m.blocks.name[a] + "' and '" + m.blocks.name[b] +
                        "' overlap at the start (their edges cross); move them apart so they at most touch");
  }
}

void ContactDetection::checkStepReach(const Model& m, double dt, double largestStepDisplacement) {
  // A pair the last scan saw more than the tolerance apart can close at most the tolerance, plus
  // twice one step's relative displacement s, before it is scanned again (update's bound
  // overshoots by one step), so an unseen contact appears with an overlap of at most 2 s. While
  // 2 s stays within d / 2 such a contact is an ordinary one, and beyond that the overlap stop
  // fires, since a corner no more than d / 2 inside a block (every edge is longer than 2 d) is
  // still nearest the face it came through. Past it, a corner can end nearer the far face and be
  // pushed on through, or beyond the block altogether, and the contact is lost without a trace.
  const double limit = 0.25 * m.roundingLength;
  if (largestStepDisplacement <= 0.5 * limit) return;  // no pair can reach 2 x that
  const Blocks& bl = m.blocks;
  const int n = bl.size();
  // Per block: a translation shared by every point (rigid blocks) and a spread on top of it
  // (rotation, or a deformable block's largest gridpoint motion), so that blocks moving together
  // do not count as approaching.
  translation_.assign(n, Vec2{});
  spread_.assign(n, 0.0);
  for (int b = 0; b < n; ++b)
    if (!bl.deformable[b]) {
      translation_[b] = dt * bl.velocity[b];
      spread_[b] = std::abs(bl.angularVelocity[b]) * dt * bl.boundingRadius[b];
    }
  for (int i = 0; i < m.gridpoints.size(); ++i) {
    const int b = m.gridpoints.block[i];
    spread_[b] = std::max(spread_[b], norm(m.gridpoints.velocity[i]) * dt);
  }
  // The detection's boxes, each grown by half the tolerance: two within their relative motion of
  // each other were within the tolerance before the step or are now.
  measureBoxes(m);
  auto moved = [&](int b) { return norm(translation_[b]) + spread_[b]; };
  for (int a = 0; a < n; ++a) {
    if (moved(a) <= 0.5 * limit) continue;  // a pair can pass the limit only if one of it moved half
    for (int b = 0; b < n; ++b) {
      if (b == a || (b < a && moved(b) > 0.5 * limit)) continue;  // a pair of fast blocks is judged once
      const double relative = norm(translation_[a] - translation_[b]) + spread_[a] + spread_[b];
      if (relative <= limit) continue;
      if (minX_[a] > maxX_[b] + relative || minX_[b] > maxX_[a] + relative || minY_[a] > maxY_[b] + relative ||
          minY_[b] > maxY_[a] + relative)
        continue;
      std::ostringstream s;
      s << "blocks '" << bl.name[a] << "' and '" << bl.name[b] << "' moved " << relative
        << " m relative to each other in the step to cycle " << m.cycle << ", time " << m.time
        << " s, within reach of each other: more than a quarter of the rounding length (" << limit
        << " m), the most one step may carry a corner towards a face if no contact is to be crossed unseen. The step ("
        << dt << " s) is too long for the speed reached: lower solver.frac, raise the joint stiffness (the step "
        << "shrinks with its square root), raise model.rounding, or make thin blocks thicker.";
      throw InstabilityError(s.str());
    }
  }
}

void ContactDetection::measureDisplacements(const Model& m) {
  // A vertex of a rigid block is displaced by at most |dc| + |dtheta| R: the centroid's move
  // plus the chord of the rotation about it; a deformable block by its gridpoints' largest.
  const Blocks& bl = m.blocks;
  displacement_.assign(bl.size(), 0.0);
  for (int b = 0; b < bl.size(); ++b)
    displacement_[b] = norm(bl.centroid[b] - scanCentroid_[b]) + std::abs(bl.rotation[b] - scanRotation_[b]) * bl.boundingRadius[b];
  for (int i = 0; i < m.gridpoints.size(); ++i) {
    const int b = m.gridpoints.block[i];
    displacement_[b] = std::max(displacement_[b], norm(m.gridpoints.position[i] - scanGridpoint_[i]));
  }
}

void ContactDetection::rescanNow(Model& m, const std::vector<int>& blocks) {
  std::vector<char> moved(m.blocks.size(), 0);
  for (const int b : blocks) moved[b] = 1;
  scan(m, &moved);
}

void ContactDetection::update(Model& m, double largestStepDisplacement) {
  // A block must be rescanned before one of its vertices has moved T from where its last scan
  // saw it, and when a scan is due every block past C goes with it. Take a pair whose later scan
  // rescanned B but not A: A was then at most C from its own reference and may go on to T, so
  // since that scan A has moved at most C + T and B at most T. With 2 T + C = tol the pair cannot
  // have closed more than the tolerance the scan looked across. A small C keeps resting blocks
  // out of the rescans of moving ones; T is then close to half the tolerance. The path travelled
  // by the fastest vertex bounds every block's further motion and costs nothing, so the
  // displacements are measured only when it has used up the margin left at the last measure.
  const double reach = 0.45 * m.contactTolerance, companion = 0.1 * m.contactTolerance;
  motionSinceScan_ += largestStepDisplacement;
  if (motionSinceScan_ <= margin_ && requested_.empty()) return;
  measureDisplacements(m);
  moved_.assign(m.blocks.size(), 0);
  // Near T already counts: a block resting just short of it would otherwise leave no margin,
  // and every step would measure without scanning.
  const bool due = *std::max_element(displacement_.begin(), displacement_.end()) > 0.9 * reach || !requested_.empty();
  for (const int b : requested_) moved_[b] = 1;
  requested_.clear();
  // Once a scan is due, every block past C goes with it: blocks in motion move at similar
  // speeds, and rescanning each as it alone crosses the limit would scan at every step.
  int count = 0;
  for (int b = 0; due && b < m.blocks.size(); ++b) {
    if (displacement_[b] > companion) moved_[b] = 1;
    count += moved_[b];
  }
  if (2 * count > m.blocks.size()) {  // most blocks: one full scan costs less bookkeeping
    scan(m);
    moved_.assign(m.blocks.size(), 1);
  } else if (count > 0) {
    scan(m, &moved_);
  }
  double largest = 0.0;
  for (int b = 0; b < m.blocks.size(); ++b)
    if (!moved_[b]) largest = std::max(largest, displacement_[b]);
  motionSinceScan_ = 0.0;
  margin_ = reach - largest;
}

}  // namespace vdec
