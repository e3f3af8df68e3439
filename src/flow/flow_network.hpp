#pragma once
// The domain network of fracture flow (1.3.3, Fig. 1.3-2e), formed from the contacts as they are
// now. Knots: contacts, those of the same two blocks within a quarter of the shorter one's length
// of each other joined into one. Sides: where a knot meets each of its two blocks. Walking a
// block's boundary counter-clockwise from a side to the next and crossing at that knot to the
// other block, and on, closes a loop around one void: a domain. The loop that goes around the
// outside of the model is no domain: its knots are the mouths of joints open to the outside.
// Built afresh every step, in an order that depends only on the present contacts; the fluid the
// domains hold passes to the new ones where the contacts changed.
#include "core/model.hpp"

namespace vdec {

// The pressure of the initial field at a point: hydrostatic below the water table, else the
// initial pressure.
double initialPressure(const Model& model, Vec2 at);

// Forms the network from the contacts. `carry`: the domains' fluid passes from the network
// before; otherwise (the flow coming on) every domain starts at the initial pressure field.
void buildFlowNetwork(Model& model, bool carry);

// The pressure a FlowBoundary holds at a point now.
double boundaryValue(const Model& model, const FlowBoundary& boundary, Vec2 at);

// Calls piece(vertex, t0, t1) for each part of an edge (vertex to next vertex, from t0 to t1 of
// its length) on the boundary from side s to the next side along its block.
template <class Piece>
void walkSide(const Vertices& vx, const std::vector<FlowSide>& sides, int s, Piece&& piece) {
  const FlowSide& from = sides[s];
  const FlowSide& to = sides[from.next];
  int e = from.vertex;
  double t0 = from.t;
  for (bool first = true;; first = false) {
    const bool last = e == to.vertex && (!first || !from.wraps);
    const double t1 = last ? to.t : 1.0;
    if (t1 > t0) piece(e, t0, t1);
    if (last) break;
    e = vx.next[e];
    t0 = 0.0;
  }
}

}  // namespace vdec
