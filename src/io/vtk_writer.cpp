#include "io/vtk_writer.hpp"

#include <cstdio>
#include <filesystem>
#include <limits>
#include <sstream>

#include "motion/strain_modes.hpp"
#include "contact/contact_geometry.hpp"
#include "core/errors.hpp"
#include "io/atomic_file.hpp"
#include "structure/rock_point.hpp"

namespace vdec {

namespace {

// VTK cell types.
constexpr int kVertex = 1, kLine = 3, kTriangle = 5, kPolygon = 7;

struct Grid {
  std::vector<Vec2> points;
  std::vector<std::vector<int>> cells;
  std::vector<int> types;
  // Point data: displacement and velocity (rigid block vertices take their block's).
  std::vector<Vec2> displacement, velocity;
  // Cell data.
  std::vector<int> kind;  // 0 zone, 1 rigid block, 2 contact, 3 fluid domain, 4 flow knot, 5 beam element, 6 cable element, 7 bolt reinforcement
  std::vector<int> block;
  std::vector<double> sxx, syy, sxy, szz, normalForce, shearForce;
  bool fluid = false;  // the fluid's arrays below, with [fluid] only
  std::vector<double> pressure, area, flow, aperture;
  bool beams = false;  // the beams' arrays below, with beams only
  std::vector<double> axialForce, beamShear, moment0, moment1;
  // Point data of the boundary conditions, so that a picture can show them: the DrivenDof bits
  // of a gridpoint or of a rigid vertex's block, and the loaded edges' force on each gridpoint.
  std::vector<int> driven;
  std::vector<Vec2> boundaryLoad;
};

void boundaryConditions(const Model& m, Grid& g) {
  g.driven.assign(g.points.size(), 0);
  g.boundaryLoad.assign(g.points.size(), Vec2{});
  for (int i = 0; i < m.gridpoints.size(); ++i) g.driven[i] = m.gridpoints.driven[i] & (DriveX | DriveY);
  for (std::size_t c = 0; c < g.cells.size(); ++c)
    if (g.kind[c] == 1)
      for (int p : g.cells[c]) g.driven[p] = m.blocks.driven[g.block[c]] & DriveAll;
  for (const LoadedEdge& e : m.loadedEdges) {
    const Vec2 force = m.loadedEdgeForce(e);
    g.boundaryLoad[e.from] += 0.5 * force;
    g.boundaryLoad[e.to] += 0.5 * force;
  }
}

void cellDefaults(Grid& g, int kind, int block) {
  g.kind.push_back(kind);
  g.block.push_back(block);
  for (auto* v : {&g.sxx, &g.syy, &g.sxy, &g.szz, &g.normalForce, &g.shearForce}) v->push_back(0.0);
  if (g.fluid)
    for (auto* v : {&g.pressure, &g.area, &g.flow, &g.aperture}) v->push_back(0.0);
  if (g.beams)
    for (auto* v : {&g.axialForce, &g.beamShear, &g.moment0, &g.moment1}) v->push_back(0.0);
}

// A vertex cell at `at`, of no displacement or velocity.
void pointCell(Grid& g, Vec2 at, int kind, int block) {
  g.cells.push_back({static_cast<int>(g.points.size())});
  g.points.push_back(at);
  g.displacement.push_back({});
  g.velocity.push_back({});
  g.types.push_back(kVertex);
  cellDefaults(g, kind, block);
}

Grid collect(const Model& m) {
  Grid g;
  g.fluid = m.flow.present;
  g.beams = m.structures.any();  // beams' and cables' arrays alike
  const Gridpoints& gp = m.gridpoints;
  for (int i = 0; i < gp.size(); ++i) {
    g.points.push_back(gp.position[i]);
    g.displacement.push_back(gp.position[i] - gp.initialPosition[i]);
    g.velocity.push_back(gp.velocity[i]);
  }
  for (int z = 0; z < m.zones.size(); ++z) {
    const auto& n = m.zones.gridpoint[z];
    g.cells.push_back({n[0], n[1], n[2]});
    g.types.push_back(kTriangle);
    cellDefaults(g, 0, m.zones.block[z]);
    g.sxx.back() = m.zones.sxx[z];
    g.syy.back() = m.zones.syy[z];
    g.sxy.back() = m.zones.sxy[z];
    g.szz.back() = m.zones.szz[z];
  }
  const Blocks& b = m.blocks;
  for (int k = 0; k < b.size(); ++k) {
    if (b.deformable[k] || b.excavated(k)) continue;
    const bool strained = m.strainModes.holds(k);
    std::vector<int> cell;
    for (int v = b.firstVertex[k]; v < b.firstVertex[k] + b.vertexCount[k]; ++v) {
      cell.push_back(static_cast<int>(g.points.size()));
      g.points.push_back(m.vertices.geometry[v].position);
      // Where the vertex started: the block's first centroid plus the vertex at zero rotation.
      g.displacement.push_back(m.vertices.geometry[v].position - (b.initialCentroid[k] + m.vertices.localPosition[v]));
      const Vec2 r = m.vertices.geometry[v].position - b.centroid[k];
      g.velocity.push_back(b.velocity[k] + b.angularVelocity[k] * perp(r) + (strained ? strainVelocity(m, k, r) : Vec2{}));
    }
    g.cells.push_back(cell);
    g.types.push_back(kPolygon);
    cellDefaults(g, 1, k);
    if (strained) {
      // A simply-deformable block's uniform stress, in the world's axes.
      double szz = 0.0;
      const Sym2 s = inWorldAxes(m, k, presentStress(m, k, szz));
      g.sxx.back() = s.xx, g.syy.back() = s.yy, g.sxy.back() = s.xy, g.szz.back() = szz;
    }
  }
  for (const Contact& c : m.contacts) {
    pointCell(g, contactGeometry(m, c).point, 2, c.blockA);
    g.normalForce.back() = m.normalForce(c);
    g.shearForce.back() = m.shearForce(c);
  }
  for (const FlowDomain& d : m.flow.domains) {
    pointCell(g, d.centre, 3, -1);
    g.pressure.back() = d.pressure;
    g.area.back() = d.area;
  }
  for (const FlowKnot& k : m.flow.knots) {
    pointCell(g, k.point, 4, k.blockA);
    g.flow.back() = k.flow;
    g.aperture.back() = k.aperture;
  }
  // Beam elements: lines between their nodes (block -1); the nodes carry their displacement and velocity.
  const BeamNodes& nd = m.structures.nodes;
  const int firstNode = static_cast<int>(g.points.size());
  for (int i = 0; i < nd.size(); ++i) {
    g.points.push_back(nd.position[i]);
    g.displacement.push_back(nd.position[i] - nd.initialPosition[i]);
    g.velocity.push_back(nd.velocity[i]);
  }
  const BeamElements& el = m.structures.elements;
  for (int e = 0; e < el.size(); ++e) {
    g.cells.push_back({firstNode + el.node[e][0], firstNode + el.node[e][1]});
    g.types.push_back(kLine);
    cellDefaults(g, 5, -1);
    g.axialForce.back() = el.axialForce[e];
    g.beamShear.back() = el.shearForce[e];
    g.moment0.back() = el.endMoment[e][0];
    g.moment1.back() = el.endMoment[e][1];
  }
  // Cable elements: lines between their nodes, which sit where they were installed, moved along
  // the cable by their displacement.
  const Structures& st = m.structures;
  const CableNodes& cn = st.cableNodes;
  const int firstCableNode = static_cast<int>(g.points.size());
  for (int i = 0; i < cn.size(); ++i) {
    const Vec2 along = st.cables[cn.cable[i]].direction;
    g.points.push_back(cn.position[i] + cn.displacement[i] * along);
    g.displacement.push_back(cn.displacement[i] * along);
    g.velocity.push_back(cn.velocity[i] * along);
  }
  for (int e = 0; e < st.cableElements.size(); ++e) {
    if (!st.cables[st.cableElements.cable[e]].installed) continue;
    g.cells.push_back({firstCableNode + st.cableElements.node[e][0], firstCableNode + st.cableElements.node[e][1]});
    g.types.push_back(kLine);
    cellDefaults(g, 6, -1);
    g.axialForce.back() = st.cableElements.axialForce[e];
  }
  // Bolts' reinforcements: their active length as it stands, centred where side 0 holds the joint.
  const BoltCrossings& x = st.crossings;
  for (int i = 0; i < x.size(); ++i) {
    const Bolt& bolt = st.bolts[x.bolt[i]];
    if (!bolt.installed) continue;
    const double active = st.boltMaterials[bolt.material].activeLength;
    const Vec2 span = active * bolt.direction + x.displacement[i];
    const RockPointNow at = rockPointNow(m, x.side[i][0]);
    g.cells.push_back({static_cast<int>(g.points.size()), static_cast<int>(g.points.size()) + 1});
    for (const Vec2 end : {at.position - 0.5 * active * normalized(span), at.position - 0.5 * active * normalized(span) + span}) {
      g.points.push_back(end);
      g.displacement.push_back({});
      g.velocity.push_back(at.velocity);
    }
    g.types.push_back(kLine);
    cellDefaults(g, 7, x.side[i][0].block);
    g.axialForce.back() = x.axialForce[i];
    g.beamShear.back() = x.shearForce[i];
  }
  boundaryConditions(m, g);
  return g;
}

template <class T>
void dataArray(std::ostream& out, const char* name, const std::vector<T>& values, const char* type) {
  out << "<DataArray type=\"" << type << "\" Name=\"" << name << "\" format=\"ascii\">";
  for (const T& v : values) out << v << ' ';
  out << "</DataArray>\n";
}

void vectorArray(std::ostream& out, const char* name, const std::vector<Vec2>& values) {
  out << "<DataArray type=\"Float64\" Name=\"" << name << "\" NumberOfComponents=\"3\" format=\"ascii\">";
  for (const Vec2& v : values) out << v.x << ' ' << v.y << " 0 ";
  out << "</DataArray>\n";
}

bool isSnapshotName(const std::string& name) {
  constexpr std::string_view prefix = "snapshot_", suffix = ".vtu";
  if (name.size() < prefix.size() + 9 + suffix.size() || !name.starts_with(prefix) || !name.ends_with(suffix))
    return false;
  for (std::size_t i = prefix.size(); i < name.size() - suffix.size(); ++i)
    if (name[i] < '0' || name[i] > '9') return false;
  return true;
}

}  // namespace

void VtkSeries::removeStale(const std::string& directory) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_directory(directory, ec)) return;
  std::vector<fs::path> stale;
  for (const fs::directory_entry& e : fs::directory_iterator(directory, ec)) {
    const std::string name = e.path().filename().string();
    if (name == "model.pvd" || isSnapshotName(name)) stale.push_back(e.path());
  }
  if (ec) throw OutputError(directory + ": cannot list the old VTK snapshots (" + ec.message() + ")");
  for (const fs::path& p : stale)
    if (!fs::remove(p, ec) && ec)
      throw OutputError(p.string() + ": cannot remove this VTK file of an earlier run (" + ec.message() +
                        "); remove it or choose another --out");
}

void VtkSeries::prepare() const {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(directory_, ec);
  if (ec || !fs::is_directory(directory_))
    throw OutputError(directory_ + ": cannot create the VTK directory (" +
                      (ec ? ec.message() : std::string("a file of that name is in the way")) +
                      "); choose another --out");
  // A file can be created there: the same check the results directory gets.
  AtomicFile probe((fs::path(directory_) / "model.pvd").string());
}

void VtkSeries::write(const Model& m) {
  std::error_code ec;
  std::filesystem::create_directories(directory_, ec);
  if (ec) throw OutputError(directory_ + ": cannot create the VTK directory (" + ec.message() + ")");
  char name[64];
  std::snprintf(name, sizeof name, "snapshot_%09lld.vtu", m.cycle);
  const std::string path = (std::filesystem::path(directory_) / name).string();
  const Grid g = collect(m);
  AtomicFile file(path);
  std::ostream& out = file.stream();
  out.precision(17);
  out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\">\n"
      << "<UnstructuredGrid>\n<Piece NumberOfPoints=\"" << g.points.size() << "\" NumberOfCells=\"" << g.cells.size()
      << "\">\n<Points>\n";
  vectorArray(out, "position", g.points);
  out << "</Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">";
  for (const auto& cell : g.cells)
    for (int p : cell) out << p << ' ';
  out << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">";
  long long offset = 0;
  for (const auto& cell : g.cells) out << (offset += static_cast<long long>(cell.size())) << ' ';
  out << "</DataArray>\n";
  dataArray(out, "types", g.types, "UInt8");
  out << "</Cells>\n<PointData Vectors=\"displacement\">\n";
  vectorArray(out, "displacement", g.displacement);
  vectorArray(out, "velocity", g.velocity);
  dataArray(out, "driven", g.driven, "Int32");
  vectorArray(out, "boundary_load", g.boundaryLoad);
  if (m.heat.on) {
    // The gridpoints come first among the points; the others (rigid vertices, structures'
    // nodes, cells of joints and fluid) have no temperature.
    std::vector<double> temperature(g.points.size(), std::numeric_limits<double>::quiet_NaN());
    for (int i = 0; i < m.gridpoints.size(); ++i) temperature[i] = m.heat.temperature[m.heat.nodeOfGridpoint[i]];
    dataArray(out, "temperature", temperature, "Float64");
  }
  out << "</PointData>\n<CellData>\n";
  const std::string kinds = std::string("kind (0 zone, 1 rigid block, 2 contact") +
                            (g.fluid ? ", 3 fluid domain, 4 flow knot" : "") + (g.beams ? ", 5 beam element, 6 cable element, 7 bolt reinforcement" : "") + ")";
  dataArray(out, kinds.c_str(), g.kind, "Int32");
  dataArray(out, "block", g.block, "Int32");
  dataArray(out, "sxx", g.sxx, "Float64");
  dataArray(out, "syy", g.syy, "Float64");
  dataArray(out, "sxy", g.sxy, "Float64");
  dataArray(out, "szz", g.szz, "Float64");
  dataArray(out, "normal_force", g.normalForce, "Float64");
  dataArray(out, "shear_force", g.shearForce, "Float64");
  if (g.fluid) {
    dataArray(out, "pressure", g.pressure, "Float64");
    dataArray(out, "domain_area", g.area, "Float64");
    dataArray(out, "flow", g.flow, "Float64");
    dataArray(out, "aperture", g.aperture, "Float64");
  }
  if (g.beams) {
    dataArray(out, "axial_force", g.axialForce, "Float64");
    dataArray(out, "beam_shear_force", g.beamShear, "Float64");
    dataArray(out, "moment_0", g.moment0, "Float64");
    dataArray(out, "moment_1", g.moment1, "Float64");
  }
  out << "</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
  file.commit();
  written_.emplace_back(m.time, name);
  std::ostringstream collection;
  collection.precision(17);
  collection << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\">\n<Collection>\n";
  for (const auto& [time, snapshot] : written_)
    collection << "<DataSet timestep=\"" << time << "\" file=\"" << snapshot << "\"/>\n";
  collection << "</Collection>\n</VTKFile>\n";
  writeFileAtomically((std::filesystem::path(directory_) / "model.pvd").string(), collection.str());
}

}  // namespace vdec
