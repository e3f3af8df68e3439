#include "thermal/heat.hpp"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <map>

#include "core/errors.hpp"
#include "core/shown.hpp"

namespace vdec {

namespace {

double decayFactor(const HeatDecay& decay, double t) {
  if (decay.empty()) return 1.0;
  double f = 0.0;
  for (const auto& [a, tau] : decay) f += a * std::exp(-t / tau);
  return f;
}

// The loads' power at each node at thermal time t, sources and boundary fluxes apart.
void loadsAt(const HeatField& h, double t, std::vector<double>& source, std::vector<double>& flux) {
  source.assign(h.temperature.size(), 0.0);
  flux.assign(h.temperature.size(), 0.0);
  for (std::size_t k = 0; k < h.loadNode.size(); ++k) {
    double power = h.loadPower[k] * decayFactor(h.decays[h.loadDecay[k]], t);
    if (h.loadHistory[k] >= 0) power *= h.histories[h.loadHistory[k]](t);
    (h.loadBoundary[k] ? flux : source)[h.loadNode[k]] += power;
  }
}

// y = K x over all nodes.
void conduct(const HeatField& h, const std::vector<double>& x, std::vector<double>& y) {
  y.assign(x.size(), 0.0);
  for (std::size_t i = 0; i < x.size(); ++i) {
    double sum = 0.0;
    for (int e = h.rowStart[i]; e < h.rowStart[i + 1]; ++e) sum += h.conductance[e] * x[h.column[e]];
    y[i] = sum;
  }
}

// The convection of each node: its total h L / 2 and that times its ambient temperature; and its
// radiation linearised about the present temperature T_n: c (T_a^4 - T^4) ~ c (T_a^4 + 3 T_n^4)
// - 4 c T_n^3 T, a conductance 4 c T_n^3 towards the load c (T_a^4 + 3 T_n^4).
void convectionOf(const HeatField& h, std::vector<double>& conductance, std::vector<double>& drive) {
  conductance.assign(h.temperature.size(), 0.0);
  drive.assign(h.temperature.size(), 0.0);
  for (std::size_t k = 0; k < h.convectionNode.size(); ++k) {
    conductance[h.convectionNode[k]] += h.convectionConductance[k];
    drive[h.convectionNode[k]] += h.convectionConductance[k] * h.convectionAmbient[k];
  }
  for (std::size_t k = 0; k < h.radiationNode.size(); ++k) {
    const int i = h.radiationNode[k];
    const double T = h.temperature[i], c = h.radiationCoefficient[k], Ta = h.radiationAmbient[k];
    if (!(T > 0.0))
      throw InstabilityError("a radiating node's temperature is " + shown(T) + " after " + std::to_string(h.steps) +
                             " thermal steps: radiation needs absolute temperatures (kelvin) above zero; give every "
                             "temperature of the scene in kelvin");
    conductance[i] += 4.0 * c * T * T * T;
    drive[i] += c * (Ta * Ta * Ta * Ta + 3.0 * T * T * T * T);
  }
}

// What the steps of one advance share: the factorised C + theta dt (K + H) on the free nodes
// (theta > 0), and the per-node buffers, sized once, so that a step allocates nothing.
struct StepWork {
  std::vector<int> index;  // node -> row among the free nodes, -1 for a fixed node
  int free = 0;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver;
  double dt = 0.0;
  std::vector<double> source, flux, convection, drive, KT, before, mid, KMid;
  Eigen::VectorXd b, x;
};

void factorise(const HeatField& h, const std::vector<double>& convection, double dt, StepWork& system) {
  system.index.assign(h.temperature.size(), -1);
  int free = 0;
  for (int i = 0; i < h.size(); ++i)
    if (!h.fixed[i]) system.index[i] = free++;
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < h.size(); ++i) {
    const int row = system.index[i];
    if (row < 0) continue;
    entries.emplace_back(row, row, h.capacity[i] + h.theta * dt * convection[i]);
    for (int e = h.rowStart[i]; e < h.rowStart[i + 1]; ++e)
      if (system.index[h.column[e]] >= 0) entries.emplace_back(row, system.index[h.column[e]], h.theta * dt * h.conductance[e]);
  }
  system.free = free;
  Eigen::SparseMatrix<double> A(free, free);
  A.setFromTriplets(entries.begin(), entries.end());
  system.solver.compute(A);
  if (system.solver.info() != Eigen::Success)
    throw InstabilityError("the thermal system C + theta dt K could not be factorised: check that every zone of a block "
                         "with heat has a positive specific heat and density");
  system.dt = dt;
}

void step(HeatField& h, double dt, StepWork& system) {
  const int n = h.size();
  std::vector<double> &source = system.source, &flux = system.flux, &convection = system.convection;
  std::vector<double> &drive = system.drive, &KT = system.KT, &before = system.before;
  loadsAt(h, h.time + h.theta * dt, source, flux);
  convectionOf(h, convection, drive);
  before = h.temperature;
  // Held nodes with a history take their temperature at the step's end now: the step's
  // conduction sees them move from the old value to the new.
  for (int i = 0; i < n; ++i)
    if (h.fixed[i] && h.fixedHistory[i] >= 0) h.temperature[i] = h.fixedValue[i] * h.histories[h.fixedHistory[i]](h.time + dt);
  conduct(h, before, KT);
  if (h.theta == 0.0) {
    for (const int i : h.radiationNode) {
      // The radiation's conductance grows as T^3: the explicit step may no longer be stable.
      double row = convection[i];
      for (int e = h.rowStart[i]; e < h.rowStart[i + 1]; ++e) row += std::abs(h.conductance[e]);
      if (!h.fixed[i] && dt * row > 2.0 * h.capacity[i])
        throw InstabilityError("the explicit thermal step " + shown(dt) + " s is above the stable step " +
                               shown(2.0 * h.capacity[i] / row) + " s of a radiating node at " + shown(before[i]) +
                               " K (its linearised conductance 4 epsilon sigma T^3 grows with T): lower heat.step, or "
                               "give theta > 0");
    }
    for (int i = 0; i < n; ++i)
      if (!h.fixed[i])
        h.temperature[i] += dt * (source[i] + flux[i] + drive[i] - convection[i] * before[i] - KT[i]) / h.capacity[i];
  } else {
    // Radiation's linearised conductance moves with the temperature: factorise every step then.
    if (system.dt != dt || !h.radiationNode.empty()) {
      factorise(h, convection, dt, system);
      ++h.factorisations;
    }
    Eigen::VectorXd& b = system.b;
    b.resize(system.free);
    for (int i = 0; i < n; ++i) {
      const int row = system.index[i];
      if (row < 0) continue;
      // Held neighbours at the end of the step are known.
      double fixedPart = 0.0;
      for (int e = h.rowStart[i]; e < h.rowStart[i + 1]; ++e)
        if (h.fixed[h.column[e]]) fixedPart += h.conductance[e] * h.temperature[h.column[e]];
      b[row] = h.capacity[i] * before[i] - (1.0 - h.theta) * dt * (KT[i] + convection[i] * before[i]) -
               h.theta * dt * fixedPart + dt * (source[i] + flux[i] + drive[i]);
    }
    system.x = system.solver.solve(b);
    for (int i = 0; i < n; ++i)
      if (system.index[i] >= 0) h.temperature[i] = system.x[system.index[i]];
  }
  // The balance over the free nodes: their stored change is what the loads, the convection and
  // the fixed nodes gave them (K's rows sum to zero: conduction among free nodes cancels).
  std::vector<double> &mid = system.mid, &KMid = system.KMid;
  mid.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) mid[i] = (1.0 - h.theta) * before[i] + h.theta * h.temperature[i];
  conduct(h, mid, KMid);
  for (int i = 0; i < n; ++i) {
    if (h.fixed[i]) {
      h.fixedInflow += dt * KMid[i];
      continue;
    }
    h.stored += h.capacity[i] * (h.temperature[i] - before[i]);
    h.sources += dt * source[i];
    h.boundary += dt * (flux[i] + drive[i] - convection[i] * mid[i]);
  }
  h.time += dt;
  ++h.steps;
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(h.temperature[i]))
      throw InstabilityError("a temperature is not a number after " + std::to_string(h.steps) +
                           " thermal steps: check the thermal properties and loads");
}

// The linear shape functions' gradients of a triangle, (y_j - y_k, x_k - x_j) / 2A for (i, j, k)
// in turn, on the positions the conductance was assembled on (the scene's); returns the area.
double shapeGradients(const Model& m, int z, Vec2 (&grad)[3]) {
  const auto& p = m.zones.gridpoint[z];
  const Vec2 corner[3] = {m.gridpoints.initialPosition[p[0]], m.gridpoints.initialPosition[p[1]],
                          m.gridpoints.initialPosition[p[2]]};
  const double area = 0.5 * cross(corner[1] - corner[0], corner[2] - corner[0]);
  for (int i = 0; i < 3; ++i) {
    const Vec2 pj = corner[(i + 1) % 3], pk = corner[(i + 2) % 3];
    grad[i] = (0.5 / area) * Vec2{pj.y - pk.y, pk.x - pj.x};
  }
  return area;
}

// k grad: the conductivity tensor, kx along the material's axis at conductivityAngle, ky across it.
Vec2 conducted(const BlockMaterial& mat, Vec2 grad) {
  const double cs = std::cos(mat.conductivityAngle), sn = std::sin(mat.conductivityAngle);
  const double kxx = mat.conductivityX * cs * cs + mat.conductivityY * sn * sn;
  const double kyy = mat.conductivityX * sn * sn + mat.conductivityY * cs * cs;
  const double kxy = (mat.conductivityX - mat.conductivityY) * sn * cs;
  return {kxx * grad.x + kxy * grad.y, kxy * grad.x + kyy * grad.y};
}

}  // namespace

void assembleHeat(Model& m) {
  HeatField& h = m.heat;
  const Zones& zn = m.zones;
  std::vector<Eigen::Triplet<double>> entries;
  h.capacity.assign(h.temperature.size(), 0.0);
  for (int z = 0; z < zn.size(); ++z) {
    const BlockMaterial& mat = m.blockMaterials[zn.material[z]];
    const auto& p = zn.gridpoint[z];
    Vec2 grad[3];
    const double area = shapeGradients(m, z, grad);
    for (int i = 0; i < 3; ++i) {
      const int ni = h.nodeOfGridpoint[p[i]];
      h.capacity[ni] += mat.density * mat.specificHeat * area / 3.0;
      for (int j = 0; j < 3; ++j)
        entries.emplace_back(ni, h.nodeOfGridpoint[p[j]], area * dot(grad[i], conducted(mat, grad[j])));
    }
  }
  Eigen::SparseMatrix<double, Eigen::RowMajor> K(h.size(), h.size());
  K.setFromTriplets(entries.begin(), entries.end());
  K.makeCompressed();
  h.rowStart.assign(K.outerIndexPtr(), K.outerIndexPtr() + h.size() + 1);
  h.column.assign(K.innerIndexPtr(), K.innerIndexPtr() + K.nonZeros());
  h.conductance.assign(K.valuePtr(), K.valuePtr() + K.nonZeros());
}

double heatStableStep(const Model& m) {
  const HeatField& h = m.heat;
  std::vector<double> convection, drive;
  convectionOf(h, convection, drive);
  double fastest = 0.0;
  for (int i = 0; i < h.size(); ++i) {
    if (h.fixed[i]) continue;
    double row = convection[i];
    for (int e = h.rowStart[i]; e < h.rowStart[i + 1]; ++e) row += std::abs(h.conductance[e]);
    fastest = std::max(fastest, row / h.capacity[i]);
  }
  return fastest > 0.0 ? 2.0 / fastest : INFINITY;
}

void advanceHeat(Model& m, double duration) {
  HeatField& h = m.heat;
  if (!h.on || !(duration > 0.0)) return;
  const double whole = std::floor(duration / h.step + 1e-9);
  double rest = duration - whole * h.step;
  if (rest <= 1e-9 * h.step) rest = 0.0;
  StepWork system;
  for (long long k = 0; k < static_cast<long long>(whole); ++k) step(h, h.step, system);
  if (rest > 0.0) step(h, rest, system);
}

namespace {

double zoneMeanTemperature(const Model& m, int z) {
  const HeatField& h = m.heat;
  const auto& p = m.zones.gridpoint[z];
  return (h.temperature[h.nodeOfGridpoint[p[0]]] + h.temperature[h.nodeOfGridpoint[p[1]]] +
          h.temperature[h.nodeOfGridpoint[p[2]]]) / 3.0;
}

}  // namespace

void applyThermalStress(Model& m) {
  Zones& zn = m.zones;
  for (int z = 0; z < zn.size(); ++z) {
    const double now = zoneMeanTemperature(m, z);
    const double dT = now - m.heat.zoneTemperature[z];
    m.heat.zoneTemperature[z] = now;
    const BlockMaterial& mat = m.blockMaterials[zn.material[z]];
    const double ds = -mat.bulk * 3.0 * mat.expansion * dT;
    zn.sxx[z] += ds;
    zn.syy[z] += ds;
    zn.szz[z] += ds;
  }
}

HeatLine heatLine(const Model& m, Vec2 from, Vec2 to) {
  const HeatField& h = m.heat;
  const Vec2 along = to - from;
  const double length = norm(along);
  const double tolerance = 1e-6 * length;
  auto onLine = [&](Vec2 p) {
    const double t = dot(p - from, along) / (length * length);
    return t >= -1e-9 && t <= 1.0 + 1e-9 && std::abs(cross(along, p - from)) / length <= tolerance;
  };
  // A zone edge is keyed by its thermal nodes, so that the zones of two blocks that meet along
  // it share it as the zones of one block do.
  std::map<std::pair<int, int>, int> zonesOnEdge;
  HeatLine line;
  std::vector<std::pair<int, int>> keys;
  for (int z = 0; z < m.zones.size(); ++z) {
    const auto& p = m.zones.gridpoint[z];
    for (int i = 0; i < 3; ++i) {
      const int a = p[i], b = p[(i + 1) % 3];
      if (!onLine(m.gridpoints.initialPosition[a]) || !onLine(m.gridpoints.initialPosition[b])) continue;
      const std::pair<int, int> key = std::minmax(h.nodeOfGridpoint[a], h.nodeOfGridpoint[b]);
      ++zonesOnEdge[key];
      line.edge.push_back(3 * z + i);
      keys.push_back(key);
    }
  }
  for (const auto& key : keys) line.share.push_back(1.0 / zonesOnEdge[key]);
  return line;
}

double heatFlowAcross(const Model& m, const HeatLine& line, Vec2 from, Vec2 to) {
  const HeatField& h = m.heat;
  const Vec2 along = to - from;
  const Vec2 normal = (1.0 / norm(along)) * Vec2{along.y, -along.x};
  double flow = 0.0;
  for (std::size_t k = 0; k < line.edge.size(); ++k) {
    const int z = line.edge[k] / 3, i = line.edge[k] % 3;
    const auto& p = m.zones.gridpoint[z];
    Vec2 grad[3];
    shapeGradients(m, z, grad);
    Vec2 gradient{0.0, 0.0};
    for (int j = 0; j < 3; ++j) gradient += h.temperature[h.nodeOfGridpoint[p[j]]] * grad[j];
    const double edge = norm(m.gridpoints.initialPosition[p[(i + 1) % 3]] - m.gridpoints.initialPosition[p[i]]);
    flow -= line.share[k] * edge * dot(conducted(m.blockMaterials[m.zones.material[z]], gradient), normal);
  }
  return flow;
}

}  // namespace vdec
