#include "io/results_writer.hpp"

#include <algorithm>
#include <unistd.h>

#include <chrono>
#include <ctime>
#include <filesystem>
#include <map>
#include <numbers>
#include <nlohmann/json.hpp>

#include "motion/strain_modes.hpp"
#include "bem/far_field.hpp"
#include "contact/contact_geometry.hpp"
#include "flow/fracture_flow.hpp"
#include "geometry/zoning.hpp"
#include "core/vector_unit.hpp"
#include "core/errors.hpp"
#include "core/interrupt.hpp"
#include "io/atomic_file.hpp"
#include "io/build_info.hpp"

namespace vdec {

const char* jointLawName(JointLaw law) {
  switch (law) {
    case JointLaw::PointContact: return "point-contact";
    case JointLaw::CoulombSlip: return "coulomb-slip";
    case JointLaw::CoulombFracture: return "coulomb-fracture";
    case JointLaw::ContinuouslyYielding: return "continuously-yielding";
  }
  return "?";
}

namespace {

// Where and when the file was written: provenance that differs between two runs of one scene,
// kept apart from the results so that comparing two runs can drop it in one place.
nlohmann::json environment(const RunEnvironment& run) {
  char host[256] = {};
  gethostname(host, sizeof host - 1);
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return {{"host", host}, {"written_utc", stamp}, {"threads", run.threads}, {"threads_option", run.threadsOption},
          {"vector_unit", vectorUnitName(vectorUnit())}};
}

// Deformable blocks: per gridpoint its initial position and displacement, per zone its centroid
// and stress, per block its zoning quality; columns of equal length, in id order.
void writeContinuum(nlohmann::json& j, const Model& m) {
  const Gridpoints& g = m.gridpoints;
  std::vector<double> x0, y0, ux, uy, vx, vy;
  std::vector<int> gBlock;
  for (int i = 0; i < g.size(); ++i) {
    gBlock.push_back(g.block[i]);
    x0.push_back(g.initialPosition[i].x);
    y0.push_back(g.initialPosition[i].y);
    ux.push_back(g.position[i].x - g.initialPosition[i].x);
    uy.push_back(g.position[i].y - g.initialPosition[i].y);
    vx.push_back(g.velocity[i].x);
    vy.push_back(g.velocity[i].y);
  }
  j["gridpoints"] = {{"block", gBlock}, {"x0", x0}, {"y0", y0}, {"displacement_x", ux}, {"displacement_y", uy},
                     {"velocity_x", vx}, {"velocity_y", vy}};
  if (m.heat.on) {
    std::vector<double> temperature;
    for (int i = 0; i < g.size(); ++i) temperature.push_back(m.heat.temperature[m.heat.nodeOfGridpoint[i]]);
    j["gridpoints"]["temperature"] = temperature;
  }
  const Zones& zn = m.zones;
  std::vector<double> cx0, cy0, area;
  std::vector<int> zBlock;
  std::map<int, Mesh> meshes;  // per block, for the quality figures
  for (int z = 0; z < zn.size(); ++z) {
    const auto& n = zn.gridpoint[z];
    const Vec2 p0 = g.initialPosition[n[0]], p1 = g.initialPosition[n[1]], p2 = g.initialPosition[n[2]];
    const Vec2 c = (1.0 / 3.0) * (p0 + p1 + p2);
    zBlock.push_back(zn.block[z]);
    cx0.push_back(c.x);
    cy0.push_back(c.y);
    const Vec2 q0 = g.position[n[0]], q1 = g.position[n[1]], q2 = g.position[n[2]];
    area.push_back(0.5 * cross(q1 - q0, q2 - q0));
    Mesh& mesh = meshes[zn.block[z]];
    const int base = static_cast<int>(mesh.nodes.size());
    mesh.nodes.insert(mesh.nodes.end(), {p0, p1, p2});
    mesh.triangles.push_back({base, base + 1, base + 2});
  }
  j["zones"] = {{"block", zBlock}, {"x0", cx0}, {"y0", cy0}, {"area", area}, {"sxx", zn.sxx},
                {"syy", zn.syy}, {"sxy", zn.sxy}, {"szz", zn.szz}, {"plastic_state", zn.plasticState}};
  nlohmann::json quality = nlohmann::json::object();
  for (const auto& [block, mesh] : meshes) {
    const MeshQuality q = meshQuality(mesh);
    quality[m.blocks.name[block]] = {{"zones", mesh.triangles.size()},
                                     {"min_angle_degrees", q.minAngleDegrees},
                                     {"max_aspect_ratio", q.maxAspectRatio}};
  }
  j["zoning"] = quality;
}

// Beams: their nodes (initial position, displacement, rotation), elements (forces and end
// moments of the last step) and ties (the force on the node, broken, slipping).
void writeStructures(nlohmann::json& j, const Model& m) {
  const Structures& st = m.structures;
  const BeamNodes& nd = st.nodes;
  const BeamElements& el = st.elements;
  std::vector<double> x0, y0, ux, uy, rotation, mass;
  for (int i = 0; i < nd.size(); ++i) {
    x0.push_back(nd.initialPosition[i].x);
    y0.push_back(nd.initialPosition[i].y);
    ux.push_back(nd.position[i].x - nd.initialPosition[i].x);
    uy.push_back(nd.position[i].y - nd.initialPosition[i].y);
    rotation.push_back(nd.rotation[i]);
    mass.push_back(nd.mass[i]);
  }
  std::vector<int> node0, node1;
  std::vector<double> cx0, cy0, moment0, moment1;
  for (int e = 0; e < el.size(); ++e) {
    node0.push_back(el.node[e][0]);
    node1.push_back(el.node[e][1]);
    const Vec2 centre = 0.5 * (nd.initialPosition[el.node[e][0]] + nd.initialPosition[el.node[e][1]]);
    cx0.push_back(centre.x);
    cy0.push_back(centre.y);
    moment0.push_back(el.endMoment[e][0]);
    moment1.push_back(el.endMoment[e][1]);
  }
  std::vector<int> tieNode, tieBlock, tieZone, broken, slipping;
  std::vector<double> fx, fy;
  for (const BeamTie& t : st.ties) {
    tieNode.push_back(t.node);
    tieBlock.push_back(t.block);
    tieZone.push_back(t.zone);
    fx.push_back(t.force.x);
    fy.push_back(t.force.y);
    broken.push_back(t.broken);
    slipping.push_back(t.slipping);
  }
  std::vector<std::string> names;
  std::vector<int> installed;
  for (const Beam& b : st.beams) {
    names.push_back(b.name);
    installed.push_back(b.installed);
  }
  j["beams"] = {{"names", names},
                {"installed", installed},
                {"nodes", {{"beam", nd.beam}, {"x0", x0}, {"y0", y0}, {"displacement_x", ux}, {"displacement_y", uy},
                           {"rotation", rotation}, {"mass", mass}}},
                {"elements", {{"beam", el.beam}, {"node_0", node0}, {"node_1", node1}, {"x0", cx0}, {"y0", cy0},
                              {"length", el.restLength}, {"axial_force", el.axialForce}, {"shear_force", el.shearForce},
                              {"moment_0", moment0}, {"moment_1", moment1}}},
                {"ties", {{"node", tieNode}, {"block", tieBlock}, {"zone", tieZone}, {"force_x", fx}, {"force_y", fy},
                          {"broken", broken}, {"slipping", slipping}}}};
}

// Cables: their nodes (position as installed, displacement and slip along the cable, the grout's
// force, whether grouted and slipping) and elements (axial force).
void writeCables(nlohmann::json& j, const Model& m) {
  const Structures& st = m.structures;
  const CableNodes& nd = st.cableNodes;
  std::vector<double> x0, y0;
  std::vector<int> grouted;
  for (int i = 0; i < nd.size(); ++i) {
    x0.push_back(nd.position[i].x);
    y0.push_back(nd.position[i].y);
    grouted.push_back(nd.hold[i].block >= 0);
  }
  std::vector<int> node0, node1;
  for (const auto& n : st.cableElements.node) {
    node0.push_back(n[0]);
    node1.push_back(n[1]);
  }
  std::vector<std::string> names;
  std::vector<int> installed;
  for (const Cable& c : st.cables) {
    names.push_back(c.name);
    installed.push_back(c.installed);
  }
  j["cables"] = {{"names", names},
                 {"installed", installed},
                 {"nodes", {{"cable", nd.cable}, {"x0", x0}, {"y0", y0}, {"displacement", nd.displacement},
                            {"slip", nd.slip}, {"bond_force", nd.bondForce}, {"grouted", grouted}, {"slipping", nd.slipping},
                            {"mass", nd.mass}}},
                 {"elements", {{"cable", st.cableElements.cable}, {"node_0", node0}, {"node_1", node1},
                               {"length", st.cableElements.restLength}, {"axial_force", st.cableElements.axialForce}}}};
}

// Bolts: their reinforcements at the joints they cross (where, which blocks, the forces and
// displacements, broken when a side was excavated).
void writeBolts(nlohmann::json& j, const Model& m) {
  const Structures& st = m.structures;
  const BoltCrossings& x = st.crossings;
  std::vector<double> px, py, shearDisplacement;
  std::vector<int> block0, block1;
  for (int i = 0; i < x.size(); ++i) {
    px.push_back(x.point[i].x);
    py.push_back(x.point[i].y);
    shearDisplacement.push_back(dot(x.displacement[i], perp(st.bolts[x.bolt[i]].direction)));
    block0.push_back(x.side[i][0].block);
    block1.push_back(x.side[i][1].block);
  }
  std::vector<std::string> names;
  std::vector<int> installed;
  for (const Bolt& b : st.bolts) {
    names.push_back(b.name);
    installed.push_back(b.installed);
  }
  j["bolts"] = {{"names", names},
                {"installed", installed},
                {"reinforcements", {{"bolt", x.bolt}, {"x", px}, {"y", py}, {"block_0", block0}, {"block_1", block1},
                                    {"axial_force", x.axialForce}, {"shear_force", x.shearForce},
                                    {"axial_displacement", x.axialDisplacement}, {"shear_displacement", shearDisplacement},
                                    {"broken", x.broken}}}};
}

// The boundary-element far field: its nodes (as installed, their displacement and the region's
// force on them), and the cost of forming its stiffness.
void writeBoundaryElements(nlohmann::json& j, const Model& m) {
  const BoundaryElementField& be = m.boundaryElements;
  std::vector<double> x, y, ux, uy, fx, fy;
  std::vector<int> joined;
  for (int i = 0; i < be.size(); ++i) {
    const Vec2 u = boundaryElementNodeDisplacement(m, i);
    x.push_back(be.node[i].x);
    y.push_back(be.node[i].y);
    ux.push_back(u.x);
    uy.push_back(u.y);
    fx.push_back(be.force[i].x);
    fy.push_back(be.force[i].y);
    joined.push_back(be.firstMember[i + 1] - be.firstMember[i]);
  }
  j["boundary_elements"] = {{"nodes", be.size()}, {"half_plane", be.halfPlane}, {"closed", be.closed},
                            {"build_seconds", be.buildSeconds},
                            {"interface", {{"x0", x}, {"y0", y}, {"displacement_x", ux}, {"displacement_y", uy},
                                           {"force_x", fx}, {"force_y", fy}, {"points", joined}}}};
}

// Heat conduction: the thermal clock and steps, and the heat balance since the start.
void writeHeat(nlohmann::json& j, const Model& m) {
  const HeatField& h = m.heat;
  int fixed = 0;
  for (const char f : h.fixed) fixed += f;
  j["heat"] = {{"time", h.time}, {"steps", h.steps}, {"step", h.step}, {"theta", h.theta}, {"nodes", h.size()}, {"fixed_nodes", fixed}, {"factorisations", h.factorisations},
               {"balance", {{"stored", h.stored}, {"sources", h.sources}, {"boundary", h.boundary},
                            {"fixed", h.fixedInflow}, {"imbalance", h.stored - h.sources - h.boundary - h.fixedInflow}}}};
  if (std::isfinite(h.stableStep)) j["heat"]["stable_step"] = h.stableStep;  // absent when every node is held
}

// Fluid in the joints: the domains (at their present centres), the knots (at their present
// points) and the fluid balance.
void writeFlow(nlohmann::json& j, const Model& m) {
  const FlowState& fs = m.flow;
  std::vector<double> dx, dy, pressure, area, content, saturation;
  std::vector<int> dBlock, fixed, atFloor;
  int floorCount = 0;
  for (const FlowDomain& d : fs.domains) {
    dx.push_back(d.centre.x);
    dy.push_back(d.centre.y);
    dBlock.push_back(-1);
    pressure.push_back(d.pressure);
    area.push_back(d.area);
    content.push_back(d.content);
    saturation.push_back(std::min(d.content / d.area, 1.0));
    fixed.push_back(d.fixed);
    atFloor.push_back(d.atMinimumArea);
    floorCount += d.atMinimumArea;
  }
  j["domains"] = {{"x0", dx}, {"y0", dy}, {"block", dBlock}, {"pressure", pressure}, {"area", area},
                  {"content", content}, {"saturation", saturation}, {"fixed", fixed}, {"at_minimum_area", atFloor}};
  std::vector<double> kx, ky, aperture, length, flow, conductance;
  std::vector<int> kBlock, kOther, d0, d1, held;
  std::vector<std::string> boundary;
  for (const FlowKnot& k : fs.knots) {
    kx.push_back(k.point.x);
    ky.push_back(k.point.y);
    kBlock.push_back(k.blockA);
    kOther.push_back(k.blockB);
    aperture.push_back(k.aperture);
    length.push_back(k.length);
    flow.push_back(k.flow);
    conductance.push_back(knotConductance(m, k));
    d0.push_back(k.domain[0]);
    d1.push_back(k.domain[1]);
    boundary.push_back(k.boundary >= 0 ? fs.boundaries[k.boundary].name : "");
    held.push_back(k.boundary >= 0);
  }
  j["knots"] = {{"x0", kx}, {"y0", ky}, {"block", kBlock}, {"block_b", kOther}, {"aperture", aperture},
                {"length", length}, {"flow", flow}, {"conductance", conductance}, {"domain_0", d0}, {"domain_1", d1},
                {"boundary", boundary}, {"held", held}};
  const FlowTotals& t = fs.totals;
  j["fluid"] = {{"flowing", fs.on},
                {"domains", fs.domains.size()},
                {"knots", fs.knots.size()},
                {"min_domain_area", fs.fluid.minDomainArea},
                {"domains_at_minimum_area", floorCount},
                {"sub_step", fs.subStep},
                {"sub_steps_last_step", fs.subSteps},
                {"sub_steps_total", t.subSteps},
                {"solve_iterations_last_step", fs.solveIterations},
                {"network_changes", t.networkChanges},
                {"balance", {{"inflow", t.inflow},
                             {"outflow", t.outflow},
                             {"content", flowContent(m)},
                             {"initial_content", t.initialContent},
                             {"created", t.created},
                             {"removed", t.removed},
                             {"imbalance", flowImbalance(m)}}}};
}


}  // namespace

void prepareOutputDirectory(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw OutputError(dir + ": not a directory; --out names the directory results.json is written in");
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir, ec))
    throw OutputError(dir + ": cannot create the output directory (" + (ec ? ec.message() : "no reason given") +
                      "); choose another --out");
  const fs::path results = fs::path(dir) / "results.json";
  const fs::file_status status = fs::symlink_status(results, ec);
  if (fs::is_directory(status))
    throw OutputError(results.string() + ": a directory is in the way of the results; remove it or choose another --out");
  // A file can be created next to results.json (and renamed, as writeResults will).
  AtomicFile probe(results.string());
  if (fs::exists(status) && !fs::remove(results, ec) && ec)
    throw OutputError(results.string() + ": cannot remove the results of an earlier run (" + ec.message() +
                      "); remove it or choose another --out");
}

void writeResults(const std::string& dir, const Scene& scene, const RunReport& report, double setupSeconds,
                  const RunEnvironment& environmentOfRun) {
  using nlohmann::json;
  const Model& m = scene.model;
  json j;
  j["schema"] = "vdec.results/1";
  j["software"] = {{"name", "vdec"},
                   {"version", build::version},
                   {"git_commit", build::gitCommit},
                   {"build_type", build::buildType},
                   {"compiler", build::compiler}};
  j["environment"] = environment(environmentOfRun);
  j["scene"] = {{"path", scene.path}, {"sha256", scene.sha256}, {"overrides", scene.overrides}, {"title", scene.title},
                {"warnings", scene.warnings}};
  if (!environmentOfRun.restartFile.empty())
    j["scene"]["restart"] = {{"file", environmentOfRun.restartFile}, {"phases_done", environmentOfRun.restartPhases}};
  json profile = json::object();
  for (const StageTiming& s : report.profile) profile[s.name] = s.seconds;
  j["run"] = {{"cycles", report.cycles},
              {"time", report.time},
              {"dt", report.dt},
              {"wall_seconds", report.wallSeconds},
              {"setup_seconds", setupSeconds},
              {"stages", report.stages},
              {"stop_reason", report.stopReason},
              {"interrupted", report.interruptSignal != 0},
              {"signal", signalName(report.interruptSignal)},
              {"error", report.error},
              {"exit_code", report.errorCode},
              {"contact_detection_scans", report.detectionScans},
              {"static_solve_seconds", report.staticSolveSeconds >= 0 ? nlohmann::json(report.staticSolveSeconds) : nlohmann::json()},
              {"static_solve_residual", report.staticSolveResidual >= 0 ? nlohmann::json(report.staticSolveResidual) : nlohmann::json()},
              {"static_solve_passes", report.staticSolvePasses},
              {"static_solve_factorisations", report.staticSolveFactorisations},
              {"static_solve_unknowns", report.staticSolveUnknowns},
              {"static_solve_plastic_iterations", report.staticSolvePlasticIterations},
              {"unbalanced_ratio", report.lastMonitors.unbalancedRatio},
              {"stage_seconds", profile}};
  if (report.stiffnessDampingStepFactor != 1.0) j["run"]["stiffness_damping_step_factor"] = report.stiffnessDampingStepFactor;
  j["run"]["step_limits"] = nlohmann::json::object();
  for (const auto& [component, limit] : report.stepLimits) j["run"]["step_limits"][component] = limit;
  j["energy"] = {{"initial", report.energy.initial},
                 {"external_work", report.energy.externalWork},
                 {"kinetic", report.energy.kinetic},
                 {"strain", report.energy.strain},
                 {"slip_dissipation", report.energy.slipDissipation},
                 {"joint_release", report.energy.jointRelease},
                 {"plastic_dissipation", report.energy.plasticDissipation},
                 {"damping_dissipation", report.energy.dampingDissipation},
                 {"largest_excess", report.energy.largestExcess}};
  for (const BoundaryCondition& b : m.boundaryConditions)
    if (!b.dashpots.empty() || !b.rigidDashpots.empty() || !b.freeField.empty())
      j["energy"]["boundary_dissipation"] = report.energy.boundaryDissipation;
  if (m.heat.on) j["energy"]["thermal_stress"] = report.energy.thermalStress;
  if (!report.phases.empty()) {
    j["energy"]["removed"] = report.energy.removed;
    for (const Phase& phase : scene.settings.phases)
      if (phase.changes.staticSolve) j["energy"]["static_solve"] = report.energy.staticSolve;
    json phases = json::array();
    for (const PhaseReport& p : report.phases)
      phases.push_back({{"name", p.name},
                        {"stop_reason", p.stopReason},
                        {"start_cycle", p.startCycle},
                        {"cycles", p.cycles},
                        {"start_time", p.startTime},
                        {"time", p.time},
                        {"unbalanced_ratio", p.unbalancedRatio},
                        {"wall_seconds", p.wallSeconds}});
    j["phases"] = phases;
  }
  json histories = json::object();
  // The specs are in the scene; the series are in the report, in the same order.
  for (std::size_t i = 0; i < scene.histories.size() && i < report.histories.size(); ++i)
    histories[scene.histories[i].name] = {
        {"t", report.histories[i].t}, {"value", report.histories[i].value}, {"every", report.histories[i].every}};
  j["histories"] = histories;
  json blocks = json::array();
  for (int b = 0; b < m.blocks.size(); ++b) {
    const Blocks& bl = m.blocks;
    blocks.push_back({{"name", bl.name[b]},
                      {"mass", bl.mass[b]},
                      {"inertia", bl.inertia[b]},
                      {"centroid", {bl.centroid[b].x, bl.centroid[b].y}},
                      {"rotation", bl.rotation[b]},
                      {"velocity", {bl.velocity[b].x, bl.velocity[b].y}},
                      {"angular_velocity", bl.angularVelocity[b]}});
    if (bl.excavated(b)) blocks.back()["excavated"] = true;
    if (m.strainModes.holds(b)) {
      const int k = m.strainModes.of[b];
      double szz = 0.0;
      const Sym2 e = inWorldAxes(m, b, m.strainModes.strain[k]), s = inWorldAxes(m, b, presentStress(m, b, szz));
      blocks.back()["kind"] = "simply-deformable";
      blocks.back()["strain"] = {{"xx", e.xx}, {"yy", e.yy}, {"xy", e.xy}};
      blocks.back()["stress"] = {{"xx", s.xx}, {"yy", s.yy}, {"xy", s.xy}, {"zz", szz}};
    }
  }
  j["blocks"] = blocks;
  json contacts = json::array();
  for (std::size_t i = 0; i < m.contacts.size(); ++i) {
    const Contact& c = m.contacts[i];
    const FeatureHit geometry = contactGeometry(m, c);
    const Vec2 point = geometry.point;
    contacts.push_back({{"block_a", m.blocks.name[c.blockA]},
                        {"corner", c.corner - m.blocks.firstVertex[c.blockA]},
                        {"block_b", m.blocks.name[c.blockB]},
                        {"kind", c.featureKind == FeatureKind::Edge ? "corner-edge" : "corner-corner"},
                        {"joint", m.jointMaterials[c.joint].name},
                        {"law", jointLawName(m.jointMaterials[c.joint].law)},
                        {"point", {point.x, point.y}},
                        {"normal", {geometry.normal.x, geometry.normal.y}},
                        {"length", c.length},
                        {"overlap", c.overlap},
                        {"normal_force", m.normalForce(c)},
                        {"shear_force", m.shearForce(c)},
                        {"normal_displacement", c.normalDisplacement},
                        {"shear_displacement", c.shearDisplacement},
                        {"open", c.open},
                        {"slipping", c.slipping},
                        {"intact", c.intact}});
    if (m.jointMaterials[c.joint].law == JointLaw::ContinuouslyYielding) {
      contacts.back()["effective_friction"] = m.yieldingStates[i].effectiveFriction * 180.0 / std::numbers::pi;
      contacts.back()["plastic_shear_displacement"] = m.yieldingStates[i].plasticShear;
    }
  }
  j["contacts"] = contacts;
  if (m.zones.size() > 0) writeContinuum(j, m);
  if (m.flow.present) writeFlow(j, m);
  if (!m.structures.beams.empty()) writeStructures(j, m);
  if (!m.structures.cables.empty()) writeCables(j, m);
  if (!m.structures.bolts.empty()) writeBolts(j, m);
  if (m.boundaryElements.on) writeBoundaryElements(j, m);
  if (m.heat.on) writeHeat(j, m);

  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  writeFileAtomically((std::filesystem::path(dir) / "results.json").string(), j.dump(1) + "\n");
}

}  // namespace vdec
