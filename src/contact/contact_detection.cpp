#include "contact/contact_detection.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "contact/contact_geometry.hpp"
#include "core/errors.hpp"

namespace vdec {

namespace {

struct Key {
  int corner, blockB;
  bool operator<(const Key& o) const { return corner != o.corner ? corner < o.corner : blockB < o.blockB; }
  bool operator==(const Key& o) const { return corner == o.corner && blockB == o.blockB; }
};

}  // namespace

std::vector<std::pair<int, int>> ContactDetection::candidatePairs(const Model& m) {
  const int n = m.blocks.size();
  const double inflate = 0.5 * m.contactTolerance;
  minX_.assign(n, INFINITY);
  maxX_.assign(n, -INFINITY);
  minY_.assign(n, INFINITY);
  maxY_.assign(n, -INFINITY);
  for (int v = 0; v < m.vertices.size(); ++v) {
    const int b = m.vertices.block[v];
    const Vec2 p = m.vertices.position[v];
    minX_[b] = std::min(minX_[b], p.x - inflate);
    maxX_[b] = std::max(maxX_[b], p.x + inflate);
    minY_[b] = std::min(minY_[b], p.y - inflate);
    maxY_[b] = std::max(maxY_[b], p.y + inflate);
  }
  if (static_cast<int>(order_.size()) != n) {
    order_.resize(n);
    for (int i = 0; i < n; ++i) order_[i] = i;
  }
  // Insertion sort: the order from the previous scan is nearly right, so this is close to
  // linear; ties broken by id keep the result independent of history.
  auto before = [&](int a, int b) { return minX_[a] != minX_[b] ? minX_[a] < minX_[b] : a < b; };
  for (int i = 1; i < n; ++i) {
    const int key = order_[i];
    int j = i - 1;
    while (j >= 0 && before(key, order_[j])) {
      order_[j + 1] = order_[j];
      --j;
    }
    order_[j + 1] = key;
  }
  std::vector<std::pair<int, int>> pairs;
  for (int i = 0; i < n; ++i) {
    const int a = order_[i];
    for (int j = i + 1; j < n && minX_[order_[j]] <= maxX_[a]; ++j) {
      const int b = order_[j];
      if (minY_[b] > maxY_[a] || minY_[a] > maxY_[b]) continue;
      pairs.emplace_back(std::min(a, b), std::max(a, b));
    }
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

void ContactDetection::scan(Model& m) {
  ++scans_;
  motionSinceScan_ = 0.0;
  std::vector<Contact> previous = std::move(m.contacts);
  std::sort(previous.begin(), previous.end(),
            [](const Contact& a, const Contact& b) { return Key{a.corner, a.blockB} < Key{b.corner, b.blockB}; });
  std::vector<Contact> found;
  auto addCornersOf = [&](int a, int b) {
    const int first = m.blocks.firstVertex[a], last = first + m.blocks.vertexCount[a];
    for (int v = first; v < last; ++v) {
      const FeatureHit hit = nearestFeature(m, v, b);
      if (!(hit.overlap >= -m.contactTolerance)) continue;
      Contact c;
      c.corner = v;
      c.blockA = a;
      c.blockB = b;
      c.feature = hit.feature;
      c.featureKind = hit.kind;
      c.normal = hit.normal;
      c.point = hit.point;
      c.overlap = hit.overlap;
      found.push_back(c);
    }
  };
  for (const auto& [a, b] : candidatePairs(m)) {
    addCornersOf(a, b);
    addCornersOf(b, a);
  }
  std::sort(found.begin(), found.end(),
            [](const Contact& a, const Contact& b) { return Key{a.corner, a.blockB} < Key{b.corner, b.blockB}; });

  // Two corners at one spot can each see the other: keep one contact for the pair. A corner
  // that sees the other corner yields to that corner's contact on this block when the other
  // corner sees an edge (it is the one pressed into a face) or another corner. Of two mutual
  // corner-corner contacts the one that already exists stays, so that its state is kept; of two
  // new ones, the one owned by the lower vertex id.
  auto findIn = [](const std::vector<Contact>& list, int corner, int blockB) -> const Contact* {
    auto it = std::lower_bound(list.begin(), list.end(), Key{corner, blockB},
                               [](const Contact& c, const Key& k) { return Key{c.corner, c.blockB} < k; });
    return (it != list.end() && Key{it->corner, it->blockB} == Key{corner, blockB}) ? &*it : nullptr;
  };
  std::vector<Contact> kept;
  kept.reserve(found.size());
  for (const Contact& c : found) {
    if (c.featureKind == FeatureKind::Corner) {
      const Contact* reverse = findIn(found, c.feature, c.blockA);
      if (reverse) {
        const bool mutual = reverse->featureKind == FeatureKind::Corner && reverse->feature == c.corner;
        if (!mutual) continue;
        const bool cExisted = findIn(previous, c.corner, c.blockB) != nullptr;
        const bool reverseExisted = findIn(previous, reverse->corner, reverse->blockB) != nullptr;
        if (cExisted != reverseExisted ? reverseExisted : reverse->corner < c.corner) continue;
      }
    }
    kept.push_back(c);
  }

  // Carry the state of contacts that persist; initialise the new ones. A joint contact's
  // stress is its spring's from zero overlap: stress-free where the faces touch, the stress of
  // the face around it where it appears under load, open where found at a gap.
  const bool initial = m.cycle == 0;
  std::size_t p = 0;
  for (Contact& c : kept) {
    while (p < previous.size() && Key{previous[p].corner, previous[p].blockB} < Key{c.corner, c.blockB}) ++p;
    if (p < previous.size() && Key{previous[p].corner, previous[p].blockB} == Key{c.corner, c.blockB}) {
      c = previous[p];
      previous[p].slipDissipation = 0.0;  // carried, not deleted
      continue;
    }
    c.joint = m.jointMaterialFor(c.blockA, c.blockB);
    const JointMaterial& j = m.jointMaterials[c.joint];
    c.length = contactLength(m, c.corner, {c.feature, c.featureKind, c.normal, c.point, c.overlap});
    c.elasticNormalStress = j.kn * c.overlap;
    c.open = c.overlap < 0.0;
    // Model #5: only contacts present at the start are bonded rock; faces that come together
    // later have no cohesion or tensile strength.
    c.intact = initial || j.law != JointLaw::CoulombFracture;
    const double touching = 1e-6 * m.roundingLength;
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
  }
  for (const Contact& old : previous) m.deletedSlipDissipation += old.slipDissipation;
  m.contacts = std::move(kept);
}

namespace {

// Whether an edge of block a crosses an edge of block b: each edge's end points lie strictly on
// opposite sides of the other's line, by more than `touching`. Faces that touch, corners on
// faces and corners on corners are not crossings. Two blocks laid across each other like a plus
// sign overlap without a corner of either inside the other; this is what finds them.
bool edgesCross(const Model& m, int a, int b, double touching) {
  const Vertices& vx = m.vertices;
  auto side = [&](int edge, Vec2 p) { return cross(vx.edgeDirection[edge], p - vx.position[edge]); };
  const int firstA = m.blocks.firstVertex[a], lastA = firstA + m.blocks.vertexCount[a];
  const int firstB = m.blocks.firstVertex[b], lastB = firstB + m.blocks.vertexCount[b];
  for (int i = firstA; i < lastA; ++i) {
    for (int j = firstB; j < lastB; ++j) {
      const double b0 = side(i, vx.position[j]), b1 = side(i, vx.position[vx.next[j]]);
      if (!((b0 > touching && b1 < -touching) || (b0 < -touching && b1 > touching))) continue;
      const double a0 = side(j, vx.position[i]), a1 = side(j, vx.position[vx.next[i]]);
      if ((a0 > touching && a1 < -touching) || (a0 < -touching && a1 > touching)) return true;
    }
  }
  return false;
}

}  // namespace

void ContactDetection::initialise(Model& m) {
  scan(m);
  const double touching = 1e-6 * m.roundingLength;
  for (const auto& [a, b] : candidatePairs(m)) {
    if (!edgesCross(m, a, b, touching)) continue;
    throw GeometryError("blocks '" + m.blocks.name[a] + "' and '" + m.blocks.name[b] +
                        "' overlap at the start (their edges cross); move them apart so they at most touch");
  }
}

void ContactDetection::update(Model& m, double largestStepDisplacement) {
  motionSinceScan_ += largestStepDisplacement;
  if (motionSinceScan_ > 0.5 * m.contactTolerance) scan(m);
}

}  // namespace vdec
