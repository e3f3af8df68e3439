#pragma once
// Fluid flow in the joints (NUREG/CR-5429 1.4.2): the fluid, its boundary conditions and the
// network of domains (the voids between blocks, Fig. 1.3-2e) joined by flow knots (the contacts
// through which fluid passes). Plain arrays, part of the Model; flow/flow_network.hpp builds the
// network from the contacts and flow/fracture_flow.hpp runs it.
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/vec2.hpp"

namespace vdec {

// How the domain pressures advance: explicit sub-steps (the reference's scheme), backward Euler
// by a sparse solve each step, or the steady flow of the present apertures each step.
enum class FlowScheme : std::uint8_t { Explicit, Implicit, Steady };

// The [fluid] table. Pressures are total pore pressures, compression positive; with gravity the
// flow follows the gradient of p - rho_w g . x, so that a hydrostatic field does not flow.
struct FluidProperties {
  double density = 1000.0;       // rho_w, kg/m^3
  double bulkModulus = 0.0;      // K_w, Pa
  double viscosity = 0.0;        // mu, Pa s
  double yieldStress = 0.0;      // tau_y of a Bingham fluid, Pa (0: Newtonian)
  bool buckingham = false;       // Bingham flow by Buckingham's law rather than the linear one
  FlowScheme scheme = FlowScheme::Explicit;
  double initialPressure = 0.0;  // Pa, where no water table is given (or above it)
  // Of the domains whose initial pressure is zero: 1 full, 0 dry (a grout's joint before injection).
  double initialSaturation = 1.0;
  double waterTable = NAN;       // y of a hydrostatic water table (NaN: none)
  double stepFraction = 0.8;     // the fluid sub-step as a fraction of the stability limit 1.4-11
  double minDomainArea = 0.0;    // m^2 per unit thickness; the builder sets the default
};

// A [[flow_boundary]]: inside the box, the mouths of joints open to the outside of the model and
// the domains whose centre lies there are held at a pressure, or the domains there share an
// inflow rate (m^2/s per unit thickness), times the history if any.
struct FlowBoundary {
  std::string name;
  Vec2 lo, hi;
  bool inflow = false;
  double value = 0.0;
  double waterTable = NAN;  // a pressure boundary hydrostatic below this level instead of `value`
  int history = -1;        // Model::timeFunctions entry; -1: constant
  double timeOrigin = 0.0;
  bool active = true;
};

// A flow knot: one contact, or several contacts of the same two blocks at nearly the same place,
// through which the fluid passes from the domain on one side to the domain on the other.
struct FlowKnot {
  std::int64_t key = 0;        // the smallest key of its contacts: ids independent of the scan history
  int blockA = -1, blockB = -1;
  int joint = -1;              // joint material
  double length = 0.0;         // l of 1.4-8: the sum of its contacts' lengths
  double aperture = 0.0;       // hydraulic aperture a = a0 + un, bounded (1.4-9)
  Vec2 point;                  // where it is (mean of its contacts' points)
  int domain[2] = {-1, -1};    // on its two sides; -1: the outside of the model
  int boundary = -1;           // FlowBoundary holding the outside side's pressure; -1: impermeable
  double flow = 0.0;           // from domain[0] to domain[1] (or the outside), m^2/s, last sub-step
};

// One place on a block's boundary where a knot meets it: the point of a vertex (t = 0) or of
// an edge (vertex to next vertex, 0 <= t < 1).
struct FlowSide {
  int knot = -1;
  int block = -1;
  int vertex = -1;
  double t = 0.0;
  int next = -1;      // the next side along the block's ring, counter-clockwise
  bool wraps = false; // the boundary from here to `next` goes round past the ring's start (or is all of it)
  int domain = -1;    // the domain the boundary from here to `next` faces
};

// A domain holding less fluid than its volume is partly saturated at zero pressure (the joints
// take no suction, as the reference's unsaturated-saturated demarcation at a phreatic surface);
// full, its pressure is the fluid's compression K_w (content / area - 1).
inline double domainPressure(double bulkModulus, double content, double area) {
  return content > area ? bulkModulus * (content / area - 1.0) : 0.0;
}

struct FlowDomain {
  std::int64_t key = 0;         // the smallest key of its sides
  double pressure = 0.0;        // Pa
  double area = 0.0;            // m^2 per unit thickness (volume of the void)
  // The fluid it holds, as its volume at zero pressure: area (1 + p / K_w) when full, less when
  // partly saturated. Flow moves content, and the pressure follows from content and area
  // (domainPressure), so the fluid is conserved to round-off.
  double content = 0.0;
  Vec2 centre;
  double perimeter = 0.0;
  bool fixed = false;           // held at a boundary pressure
  int boundary = -1;            // the FlowBoundary holding or feeding it
  bool atMinimumArea = false;   // its area is the floor min_domain_area
  double lastChange = 0.0;      // of the pressure in the last sub-step, for the instability check
  int swings = 0;               // sub-steps in a row the change has alternated in sign and not decayed
};

// Running totals of the fluid (m^2 per unit thickness since the flow came on): the balance
// inflow - outflow + created - removed - (content - initial content) is zero to round-off.
struct FlowTotals {
  double inflow = 0.0;          // through held mouths and domains and from sources, into the model
  double outflow = 0.0;         // out of the model through held mouths and domains
  double initialContent = 0.0;  // of the domains when the flow came on
  // Content given to domains that opened (from the initial pressure field) or by a steady solve,
  // and content of domains that closed without a successor or taken by a steady solve.
  double created = 0.0;
  double removed = 0.0;
  long long subSteps = 0;
  long long networkChanges = 0;  // steps whose network had domains other than the step before's
};

struct FlowState {
  bool present = false;   // the scene has a [fluid] table
  bool on = false;        // flowing now (a phase may switch it)
  FluidProperties fluid;
  std::vector<FlowBoundary> boundaries;
  std::vector<FlowKnot> knots;
  std::vector<FlowSide> sides;
  std::vector<FlowDomain> domains;
  FlowTotals totals;
  double subStep = 0.0;          // the fluid step of the last mechanical step, s
  int subSteps = 0;              // NSFDT of the last mechanical step
  int solveIterations = 0;       // solves in the last step (implicit, steady): 1, and a Bingham fluid's Newton steps
  // The domains' net inflow over the flow through the knots, at the last sub-step: 0 in a
  // steady flow (or none); the run's unbalanced ratio includes it while the fluid flows.
  double unbalancedRatio = 0.0;
};

}  // namespace vdec
