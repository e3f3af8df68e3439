#pragma once
// Heat conduction in the zones of deformable blocks (NUREG/CR-5429 1.4.3): the thermal nodes
// (gridpoints, those of different blocks that coincide merged), their temperatures and lumped
// heat capacities, the conductance matrix of the zones, the loads and the heat balance. Plain
// arrays, part of the Model; thermal/heat.hpp advances it.
#include <array>
#include <vector>

#include "boundary/time_function.hpp"

namespace vdec {

// A load's time factor: the sum of a_k exp(-t / tau_k) over its terms, or 1 without terms.
using HeatDecay = std::vector<std::array<double, 2>>;  // (a_k, tau_k)

struct HeatField {
  bool on = false;
  double theta = 0.0;        // 0 explicit, 0.5 Crank-Nicolson, 1 backward Euler
  double step = 0.0;         // s, the thermal step
  double stableStep = 0.0;   // s, the explicit scheme's limit (Gershgorin's bound)
  double time = 0.0;         // s, the thermal clock
  long long steps = 0;
  int factorisations = 0;
  std::vector<int> nodeOfGridpoint;
  std::vector<double> temperature;  // per node
  std::vector<double> capacity;     // per node: rho c A / 3 of the zones round it (J/K per metre)
  std::vector<char> fixed;          // a node held at its temperature
  // A held node's temperature is fixedValue times its history's factor at the thermal time
  // (fixedHistory -1: none, the value itself).
  std::vector<double> fixedValue;
  std::vector<int> fixedHistory;
  std::vector<TimeFunction> histories;  // of held temperatures and loads, on the thermal clock
  // The zones' conductance matrix K (W/K per metre), all rows, compressed: row i's entries are
  // conductance[rowStart[i] .. rowStart[i + 1]) in columns column[...]. Symmetric, rows sum to zero.
  std::vector<int> rowStart, column;
  std::vector<double> conductance;
  // Loads: power (W/m) at a node times its decay's factor; `boundary` tells a flux edge's share
  // from a source's, for the balance.
  std::vector<HeatDecay> decays;    // decays[0] is none
  std::vector<int> loadNode, loadDecay, loadHistory;  // loadHistory -1: none
  std::vector<double> loadPower;
  std::vector<char> loadBoundary;
  // Convection: h L / 2 of each edge end (W/K per metre) towards its ambient temperature.
  std::vector<int> convectionNode;
  std::vector<double> convectionConductance, convectionAmbient;
  // Each zone's temperature when its thermal stress was last applied (the mean of its corners'),
  // [heat] initial_temperature at the start.
  std::vector<double> zoneTemperature;
  // Radiation: epsilon sigma L / 2 of each edge end (W/(m K^4) per metre) towards its ambient
  // temperature (kelvin), linearised about each step's start (heat.cpp).
  std::vector<int> radiationNode;
  std::vector<double> radiationCoefficient, radiationAmbient;
  // The heat balance since the start (J/m): stored = sources + boundary + fixed, to round-off.
  double stored = 0.0, sources = 0.0, boundary = 0.0, fixedInflow = 0.0;
  int size() const { return static_cast<int>(temperature.size()); }
};

}  // namespace vdec
