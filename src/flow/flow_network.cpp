#include "flow/flow_network.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "contact/contact_geometry.hpp"

namespace vdec {

namespace {

// Where a side sits on its block's boundary, for sorting: ring, place along it, then along the
// edge, then (at a vertex) the direction of the contact around the rounded corner.
struct SidePlace {
  int ring = 0, order = 0;
  double t = 0.0, turn = 0.0;
  std::int64_t key = 0;
};

bool before(const SidePlace& a, const SidePlace& b) {
  if (a.ring != b.ring) return a.ring < b.ring;
  if (a.order != b.order) return a.order < b.order;
  if (a.t != b.t) return a.t < b.t;
  if (a.turn != b.turn) return a.turn < b.turn;
  return a.key < b.key;
}

// Angle from the outward normal of the edge arriving at vertex v to `out`, in (-pi, pi]: how far
// round the corner a contact pointing out along `out` sits.
double turnAt(const Model& m, int v, Vec2 out) {
  const Vec2 d = m.vertices.geometry[m.vertices.prev[v]].edgeDirection;
  const Vec2 in{d.y, -d.x};
  return std::atan2(cross(in, out), dot(in, out));
}

struct ContactPlace {
  int contact = -1;
  std::int64_t key = 0;
  Vec2 point;
  double overlap = 0.0;
  int featureVertex = -1;
  double featureTurn = 0.0;
  double cornerTurn = 0.0;
};

double pieceLength(Vec2 a, Vec2 b) { return norm(b - a); }

}  // namespace

namespace {

// Depth below the level line through (0, y_wt), the line normal to gravity: rho_w g . (x - x_wt)
// over rho_w |g|. With gravity along -y it is y_wt - y.
double depthBelow(const Model& m, double waterTable, Vec2 at) {
  const double g = norm(m.gravity);
  return g > 0.0 ? dot(m.gravity, at - Vec2{0.0, waterTable}) / g : 0.0;
}

}  // namespace

double initialPressure(const Model& m, Vec2 at) {
  const FluidProperties& f = m.flow.fluid;
  if (std::isnan(f.waterTable)) return f.initialPressure;
  const double depth = depthBelow(m, f.waterTable, at);
  return depth > 0.0 ? f.density * norm(m.gravity) * depth : f.initialPressure;
}

double boundaryValue(const Model& m, const FlowBoundary& b, Vec2 at) {
  const double value = std::isnan(b.waterTable)
                           ? b.value
                           : m.flow.fluid.density * norm(m.gravity) * std::max(0.0, depthBelow(m, b.waterTable, at));
  return b.history < 0 ? value : value * m.timeFunctions[b.history](m.time - b.timeOrigin);
}

void buildFlowNetwork(Model& m, bool carry) {
  FlowState& fs = m.flow;
  const Vertices& vx = m.vertices;
  const int nBlocks = m.blocks.size();

  // Rings: each outline of each block, its vertices numbered along it.
  std::vector<int> ringOf(vx.size(), -1), orderOf(vx.size(), 0);
  for (int b = 0; b < nBlocks; ++b) {
    int ring = 0;
    const int first = m.blocks.firstVertex[b], last = first + m.blocks.vertexCount[b];
    for (int v0 = first; v0 < last; ++v0) {
      if (ringOf[v0] >= 0) continue;
      int v = v0, order = 0;
      do {
        ringOf[v] = ring;
        orderOf[v] = order++;
        v = vx.next[v];
      } while (v != v0 && order <= m.blocks.vertexCount[b]);
      ++ring;
    }
  }

  // Every contact where it is now.
  const int nContacts = static_cast<int>(m.contacts.size());
  std::vector<ContactPlace> places(nContacts);
  for (int i = 0; i < nContacts; ++i) {
    const Contact& c = m.contacts[i];
    const FeatureHit hit = contactGeometry(m, c);
    ContactPlace& p = places[i];
    p.contact = i;
    p.key = static_cast<std::int64_t>(c.corner) * nBlocks + c.blockB;
    p.point = hit.point;
    p.overlap = hit.overlap;
    p.featureVertex = hit.feature;
    p.cornerTurn = turnAt(m, c.corner, -1.0 * hit.normal);
    p.featureTurn = hit.kind == FeatureKind::Edge ? 0.0 : turnAt(m, hit.feature, hit.normal);
  }

  // Knots: contacts of the same two blocks within a quarter of the shorter one's length of each
  // other (the two contacts of facing gridpoints, or of a corner that faces a corner) pass the
  // fluid as one; the domain between them would be a sliver of no length.
  std::vector<int> byPair(nContacts);
  std::iota(byPair.begin(), byPair.end(), 0);
  auto pairOf = [&](int i) {
    const Contact& c = m.contacts[i];
    return std::pair{std::min(c.blockA, c.blockB), std::max(c.blockA, c.blockB)};
  };
  std::sort(byPair.begin(), byPair.end(), [&](int a, int b) {
    const auto pa = pairOf(a), pb = pairOf(b);
    return pa != pb ? pa < pb : places[a].key < places[b].key;
  });
  std::vector<int> knotOf(nContacts, -1);
  std::vector<FlowKnot> knots;
  std::vector<int> knotContact;  // the contact whose sides the knot takes (its smallest key)
  for (std::size_t start = 0; start < byPair.size();) {
    std::size_t end = start;
    while (end < byPair.size() && pairOf(byPair[end]) == pairOf(byPair[start])) ++end;
    // Join within the pair: each contact to the first knot of the pair close enough.
    const std::size_t firstKnot = knots.size();
    for (std::size_t k = start; k < end; ++k) {
      const int i = byPair[k];
      const Contact& c = m.contacts[i];
      int joined = -1;
      for (std::size_t q = firstKnot; q < knots.size() && joined < 0; ++q) {
        const Contact& other = m.contacts[knotContact[q]];
        const double reach = 0.25 * std::min(c.length, other.length);
        if (norm(places[i].point - places[knotContact[q]].point) < reach) joined = static_cast<int>(q);
      }
      if (joined < 0) {
        FlowKnot knot;
        knot.key = places[i].key;
        knot.blockA = c.blockA;
        knot.blockB = c.blockB;
        knot.joint = c.joint;
        knots.push_back(knot);
        knotContact.push_back(i);
        joined = static_cast<int>(knots.size()) - 1;
      }
      knotOf[i] = joined;
    }
    start = end;
  }
  std::vector<double> overlapSum(knots.size(), 0.0);
  std::vector<Vec2> pointSum(knots.size());
  for (int k = 0; k < nContacts; ++k) {
    const int i = byPair[k];
    FlowKnot& knot = knots[knotOf[i]];
    const double w = m.contacts[i].length;
    knot.length += w;
    overlapSum[knotOf[i]] += w * places[i].overlap;
    pointSum[knotOf[i]] += w * places[i].point;
  }
  for (std::size_t k = 0; k < knots.size(); ++k) {
    FlowKnot& knot = knots[k];
    const JointMaterial& j = m.jointMaterials[knot.joint];
    knot.point = (1.0 / knot.length) * pointSum[k];
    // 1.4-9: the aperture at zero normal stress opened by the joint's normal displacement
    // (opening positive: the negative of the rounded shapes' overlap), within its bounds.
    knot.aperture = std::clamp(j.aperture - overlapSum[k] / knot.length, j.residualAperture, j.maxAperture);
  }

  // Sides, sorted along each block's boundary: where the knot's point falls on each block's
  // polygon, next to the corner or on the edge its contact has there. Both blocks' sides sit
  // at the same point, so that which block's corner the contact belongs to (it may change from
  // step to step where two corners meet) does not move them.
  auto project = [&](Vec2 point, int v, bool alsoBefore) {
    std::pair<int, double> best{v, 0.0};
    double nearest = INFINITY;
    for (const int e : {alsoBefore ? vx.prev[v] : v, v}) {
      const VertexGeometry& g = vx.geometry[e];
      const double along = std::clamp(dot(point - g.position, g.edgeDirection), 0.0, g.edgeLength);
      const double distance = norm(g.position + along * g.edgeDirection - point);
      if (distance < nearest) {
        nearest = distance;
        best = along >= g.edgeLength ? std::pair{vx.next[e], 0.0} : std::pair{e, along / g.edgeLength};
      }
    }
    return best;
  };
  // Block areas, to tell the outside loop from a void.
  std::vector<double> blockArea(nBlocks, 0.0);
  for (int b = 0; b < nBlocks; ++b) {
    const int first = m.blocks.firstVertex[b], last = first + m.blocks.vertexCount[b];
    for (int v = first; v < last; ++v) blockArea[b] += 0.5 * cross(vx.geometry[v].position, vx.geometry[vx.next[v]].position);
  }

  // A side's point, and the walk from a side to the next along the block, piece by piece.
  auto sidePoint = [&](const FlowSide& s) {
    const VertexGeometry& g = vx.geometry[s.vertex];
    return g.position + (s.t * g.edgeLength) * g.edgeDirection;
  };
  auto other = [&](int s) { return (s % 2 == 0) ? s + 1 : s - 1; };

  // Domains: the loops of side -> next -> the knot's other side.
  struct Loop {
    std::int64_t key;
    int first = 0, count = 0;  // its sides: loopSides[first .. first + count)
    double signedArea = 0.0, perimeter = 0.0, hydraulic = 0.0;
    Vec2 centre;
    bool outside = false;
  };
  std::vector<FlowSide> sides;
  std::vector<SidePlace> sidePlace;
  std::vector<Loop> loops;
  std::vector<int> loopSides;
  std::vector<int> loopOf;
  auto walk = [&](int s, auto&& piece) { walkSide(vx, sides, s, piece); };
  // A loop's area (signed: clockwise round a void), perimeter, joint volume at the hydraulic
  // apertures and centre, from its sides' places.
  auto measure = [&](Loop& loop) {
    loop.signedArea = loop.perimeter = loop.hydraulic = 0.0;
    Vec2 weighted;
    for (int i = loop.first; i < loop.first + loop.count; ++i) {
      const int s = loopSides[i];
      double length = 0.0;
      walk(s, [&](int e, double t0, double t1) {
        const VertexGeometry& g = vx.geometry[e];
        const Vec2 p0 = g.position + (t0 * g.edgeLength) * g.edgeDirection;
        const Vec2 p1 = g.position + (t1 * g.edgeLength) * g.edgeDirection;
        const double l = pieceLength(p0, p1);
        length += l;
        weighted += (0.5 * l) * (p0 + p1);
        loop.signedArea += 0.5 * cross(p0, p1);
      });
      // Across the knot to the other block.
      const int n = sides[s].next;
      loop.signedArea += 0.5 * cross(sidePoint(sides[n]), sidePoint(sides[other(n)]));
      loop.perimeter += length;
      const double a0 = knots[sides[s].knot].aperture, a1 = knots[sides[n].knot].aperture;
      loop.hydraulic += 0.25 * length * (a0 + a1);
    }
    loop.centre = loop.perimeter > 0.0 ? (1.0 / loop.perimeter) * weighted : sidePoint(sides[loopSides[loop.first]]);
  };
  // A knot with the same void on both sides (the corners meeting diagonally at a crossing of
  // joints, or blocks touching corner to corner with the outside all round) parts nothing: it
  // leaves the network, so that the rounded corners' gap it measures is no aperture of a joint.
  for (;;) {
    sides.assign(2 * knots.size(), FlowSide{});
    sidePlace.assign(sides.size(), SidePlace{});
    loops.clear();
    loopSides.clear();
    loopOf.assign(sides.size(), -1);
    for (std::size_t k = 0; k < knots.size(); ++k) {
      const ContactPlace& p = places[knotContact[k]];
      const Contact& c = m.contacts[knotContact[k]];
      const bool edge = c.featureKind == FeatureKind::Edge;
      const auto [va, ta] = project(knots[k].point, c.corner, true);
      const auto [vb, tb] = project(knots[k].point, p.featureVertex, !edge);
      FlowSide& a = sides[2 * k];
      a.knot = static_cast<int>(k);
      a.block = c.blockA;
      a.vertex = va;
      a.t = ta;
      sidePlace[2 * k] = {ringOf[va], orderOf[va], ta, ta == 0.0 && va == c.corner ? p.cornerTurn : 0.0, 2 * knots[k].key};
      FlowSide& b = sides[2 * k + 1];
      b.knot = static_cast<int>(k);
      b.block = c.blockB;
      b.vertex = vb;
      b.t = tb;
      sidePlace[2 * k + 1] = {ringOf[vb], orderOf[vb], tb, tb == 0.0 && !edge && vb == p.featureVertex ? p.featureTurn : 0.0,
                              2 * knots[k].key + 1};
    }
    // By block (a counting sort), then along each block's boundary (a few sides each).
    std::vector<int> blockStart(nBlocks + 1, 0);
    for (const FlowSide& side : sides) ++blockStart[side.block + 1];
    for (int b = 0; b < nBlocks; ++b) blockStart[b + 1] += blockStart[b];
    std::vector<int> byBlock(sides.size()), fill(blockStart.begin(), blockStart.end() - 1);
    for (std::size_t i = 0; i < sides.size(); ++i) byBlock[fill[sides[i].block]++] = static_cast<int>(i);
    for (int b = 0; b < nBlocks; ++b)
      std::sort(byBlock.begin() + blockStart[b], byBlock.begin() + blockStart[b + 1],
                [&](int x, int y) { return before(sidePlace[x], sidePlace[y]); });
    for (std::size_t start = 0; start < byBlock.size();) {
      std::size_t end = start;
      const FlowSide& s0 = sides[byBlock[start]];
      while (end < byBlock.size() && sides[byBlock[end]].block == s0.block &&
             sidePlace[byBlock[end]].ring == sidePlace[byBlock[start]].ring)
        ++end;
      for (std::size_t k = start; k < end; ++k) sides[byBlock[k]].next = byBlock[k + 1 < end ? k + 1 : start];
      start = end;
    }
    for (std::size_t s = 0; s < sides.size(); ++s)
      sides[s].wraps = sides[s].next == static_cast<int>(s) || !before(sidePlace[s], sidePlace[sides[s].next]);
    for (std::size_t s0 = 0; s0 < sides.size(); ++s0) {
      if (loopOf[s0] >= 0) continue;
      Loop loop;
      loop.first = static_cast<int>(loopSides.size());
      loop.key = INT64_MAX;
      double smallestBlock = INFINITY;
      for (int s = static_cast<int>(s0); loopOf[s] < 0; s = other(sides[s].next)) {
        loopOf[s] = static_cast<int>(loops.size());
        loopSides.push_back(s);
        ++loop.count;
        loop.key = std::min(loop.key, sidePlace[s].key);
        smallestBlock = std::min(smallestBlock, std::abs(blockArea[sides[s].block]));
      }
      measure(loop);
      // The loop around the outside runs counter-clockwise around blocks: a positive area of the
      // order of theirs. A void's runs clockwise (negative); a closed joint's sliver is of the
      // order of its overlap times its length, far below any block's area.
      loop.outside = loop.signedArea > 0.25 * smallestBlock;
      loops.push_back(std::move(loop));
    }
    std::vector<int> kept;
    for (std::size_t k = 0; k < knots.size(); ++k)
      if (loopOf[2 * k] != loopOf[2 * k + 1]) kept.push_back(static_cast<int>(k));
    if (kept.size() == knots.size()) break;
    std::vector<FlowKnot> keptKnots;
    std::vector<int> keptContacts;
    for (const int k : kept) {
      keptKnots.push_back(knots[k]);
      keptContacts.push_back(knotContact[k]);
    }
    knots = std::move(keptKnots);
    knotContact = std::move(keptContacts);
  }

  // A joint's mouth is the corner where its blocks end, not the rounded corner's contact d in
  // from it: a mouth knot's side within 1.5 d of a block's vertex moves to that vertex, so that
  // the domain behind it holds the joint up to its end, as the knot's length (half the shared
  // face) assumes. Both blocks' sides move to their own corners, wherever the contact belongs.
  const double reach = 1.5 * m.roundingLength;
  bool moved = false;
  for (std::size_t k = 0; k < knots.size(); ++k) {
    if (!loops[loopOf[2 * k]].outside && !loops[loopOf[2 * k + 1]].outside) continue;
    for (const std::size_t s : {2 * k, 2 * k + 1}) {
      FlowSide& side = sides[s];
      if (side.t == 0.0) continue;
      const double length = vx.geometry[side.vertex].edgeLength;
      const int to = side.t * length <= reach ? side.vertex : (1.0 - side.t) * length <= reach ? vx.next[side.vertex] : -1;
      if (to < 0) continue;
      side.vertex = to;
      side.t = 0.0;
      sidePlace[s].order = orderOf[to];
      sidePlace[s].t = 0.0;
      moved = true;
    }
  }
  if (moved) {
    for (std::size_t s = 0; s < sides.size(); ++s)
      sides[s].wraps = sides[s].next == static_cast<int>(s) || !before(sidePlace[s], sidePlace[sides[s].next]);
    for (Loop& loop : loops) measure(loop);
  }

  // Domains in the order of their keys.
  std::vector<int> order;
  for (std::size_t l = 0; l < loops.size(); ++l)
    if (!loops[l].outside) order.push_back(static_cast<int>(l));
  std::sort(order.begin(), order.end(), [&](int a, int b) { return loops[a].key < loops[b].key; });
  std::vector<int> domainOfLoop(loops.size(), -1);
  std::vector<FlowDomain> domains(order.size());
  for (std::size_t d = 0; d < order.size(); ++d) {
    const Loop& loop = loops[order[d]];
    domainOfLoop[order[d]] = static_cast<int>(d);
    FlowDomain& dom = domains[d];
    dom.key = loop.key;
    dom.centre = loop.centre;
    dom.perimeter = loop.perimeter;
    // The fluid fills the joints that bound the domain at their hydraulic apertures, or the
    // void's own area where that is larger (an opening), never less than the floor.
    dom.area = std::max({loop.hydraulic, -loop.signedArea, fs.fluid.minDomainArea});
    dom.atMinimumArea = dom.area == fs.fluid.minDomainArea;
  }
  for (std::size_t s = 0; s < sides.size(); ++s) sides[s].domain = domainOfLoop[loopOf[s]];
  for (std::size_t k = 0; k < knots.size(); ++k) {
    knots[k].domain[0] = sides[2 * k].domain;
    knots[k].domain[1] = sides[2 * k + 1].domain;
  }

  // The fluid of the domains before passes to those that share a side with them now.
  const double kw = fs.fluid.bulkModulus;
  auto fill = [&](FlowDomain& d, double p) {
    d.pressure = p;
    d.content = p == 0.0 ? d.area * fs.fluid.initialSaturation : d.area * (1.0 + p / kw);
  };
  if (!carry) {
    for (FlowDomain& d : domains) fill(d, initialPressure(m, d.centre));
  } else {
    auto oldKey = [&fs](std::size_t s) {
      const FlowKnot& k = fs.knots[fs.sides[s].knot];
      return 2 * k.key + (fs.sides[s].block == k.blockA ? 0 : 1);
    };
    std::vector<std::pair<int, int>> links;  // (old domain, new domain)
    // Most steps the network is the step before's, side for side: each domain is its own successor.
    bool same = fs.sides.size() == sides.size() && fs.domains.size() == domains.size();
    for (std::size_t s = 0; same && s < sides.size(); ++s)
      same = fs.sides[s].domain == sides[s].domain && oldKey(s) == sidePlace[s].key;
    if (same) {
      for (std::size_t d = 0; d < domains.size(); ++d) links.emplace_back(static_cast<int>(d), static_cast<int>(d));
    } else {
      std::vector<std::pair<std::int64_t, int>> oldSide;
      for (std::size_t s = 0; s < fs.sides.size(); ++s)
        if (fs.sides[s].domain >= 0) oldSide.emplace_back(oldKey(s), fs.sides[s].domain);
      std::sort(oldSide.begin(), oldSide.end());
      for (std::size_t s = 0; s < sides.size(); ++s) {
        if (sides[s].domain < 0) continue;
        const auto found = std::lower_bound(oldSide.begin(), oldSide.end(), std::pair{sidePlace[s].key, -1});
        if (found != oldSide.end() && found->first == sidePlace[s].key) links.emplace_back(found->second, sides[s].domain);
      }
      std::sort(links.begin(), links.end());
      links.erase(std::unique(links.begin(), links.end()), links.end());
      bool identity = links.size() == domains.size() && links.size() == fs.domains.size();
      for (std::size_t i = 0; identity && i < links.size(); ++i)
        identity = links[i].first == static_cast<int>(i) && links[i].second == static_cast<int>(i);
      if (!identity) ++fs.totals.networkChanges;
    }
    std::vector<double> targetArea(fs.domains.size(), 0.0);
    std::vector<char> reached(domains.size(), 0);
    for (const auto& [o, d] : links) targetArea[o] += domains[d].area;
    for (FlowDomain& d : domains) d.content = 0.0;
    std::vector<char> passed(fs.domains.size(), 0);
    for (const auto& [o, d] : links) {
      domains[d].content += fs.domains[o].content * (domains[d].area / targetArea[o]);
      reached[d] = 1;
      passed[o] = 1;
    }
    for (std::size_t o = 0; o < fs.domains.size(); ++o)
      if (!passed[o]) fs.totals.removed += fs.domains[o].content;
    for (std::size_t d = 0; d < domains.size(); ++d) {
      FlowDomain& dom = domains[d];
      if (reached[d]) {
        dom.pressure = domainPressure(kw, dom.content, dom.area);
      } else {
        fill(dom, initialPressure(m, dom.centre));
        fs.totals.created += dom.content;
      }
    }
    // The instability watch follows a domain that stays the same.
    for (const auto& [o, d] : links) {
      domains[d].lastChange = fs.domains[o].lastChange;
      domains[d].swings = fs.domains[o].swings;
    }
  }

  // Boundaries: the last active one whose box holds a mouth or a domain's centre governs it.
  for (int b = 0; b < static_cast<int>(fs.boundaries.size()); ++b) {
    const FlowBoundary& fb = fs.boundaries[b];
    if (!fb.active) continue;
    auto inside = [&](Vec2 p) { return p.x >= fb.lo.x && p.x <= fb.hi.x && p.y >= fb.lo.y && p.y <= fb.hi.y; };
    if (!fb.inflow)
      for (FlowKnot& k : knots)
        if ((k.domain[0] < 0 || k.domain[1] < 0) && inside(k.point)) k.boundary = b;
    for (FlowDomain& d : domains)
      if (inside(d.centre)) {
        d.boundary = b;
        d.fixed = !fb.inflow;
      }
  }

  fs.knots = std::move(knots);
  fs.sides = std::move(sides);
  fs.domains = std::move(domains);
}

}  // namespace vdec
