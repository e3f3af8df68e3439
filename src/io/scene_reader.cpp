#include "io/scene_reader.hpp"

#include <toml++/toml.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>

#include "contact/contact_geometry.hpp"
#include "contact/deformable_outline.hpp"
#include "core/errors.hpp"
#include "core/setup_progress.hpp"
#include "geometry/block_cutting.hpp"
#include "geometry/polygon.hpp"
#include "io/sha256.hpp"
#include "io/deformable_reader.hpp"
#include "io/table_reader.hpp"
#include "zone/excavation.hpp"

namespace vdec {

namespace {

void applyOverride(toml::table& root, const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw SceneError("--set '" + text + "': expected key.path=value, e.g. solver.frac=0.2");
  const std::string path = text.substr(0, eq);
  toml::table parsed;
  try {
    parsed = toml::parse("value = " + text.substr(eq + 1), "--set '" + text + "'");
  } catch (const toml::parse_error& e) {
    throw SceneError("--set '" + text + "': the value is not valid TOML: " + std::string(e.description()));
  }
  toml::table* table = &root;
  std::size_t start = 0;
  for (;;) {
    const auto dot = path.find('.', start);
    std::string part = path.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    // "name[i]" selects the i-th table of an array of tables, e.g. joint_material[0].cohesion.
    long index = -1;
    if (const auto open = part.find('['); open != std::string::npos && part.back() == ']') {
      const std::string digits = part.substr(open + 1, part.size() - open - 2);
      if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos || digits.size() > 9)
        throw SceneError("--set '" + text + "': bad index in '" + part + "': a table number from 0");
      index = std::stol(digits);
      part = part.substr(0, open);
    }
    if (part.empty()) throw SceneError("--set '" + text + "': empty key in '" + path + "'");
    if (dot == std::string::npos) {
      if (index >= 0) throw SceneError("--set '" + text + "': the last key cannot be indexed");
      table->insert_or_assign(part, std::move(*parsed.get("value")));  // moved: keeps its source
      return;
    }
    toml::node* next = table->get(part);
    if (index >= 0) {
      toml::array* array = next ? next->as_array() : nullptr;
      if (!array || !array->is_array_of_tables() || index >= static_cast<long>(array->size()))
        throw SceneError("--set '" + text + "': '" + part + "' has no table [" + std::to_string(index) + "]");
      next = array->get(static_cast<std::size_t>(index));
    } else if (!next) {
      table->insert(part, toml::table{});
      next = table->get(part);
    }
    if (!next->is_table())
      throw SceneError("--set '" + text + "': '" + part + "' is not a table; name a table key such as "
                       "solver.frac, or one table of an array such as joint_material[0].cohesion");
    table = next->as_table();
    start = dot + 1;
  }
}

struct BlockInput {
  std::string name;
  int material = -1;
  Polygon polygon;
  std::optional<Mesh> mesh;  // a deformable block's zoning
  std::uint8_t driven = 0;
  Vec2 velocity, force;
  double angularVelocity = 0.0, moment = 0.0;
  int velocityHistory = -1;
  std::string where;  // for geometry errors
};

// The continuously yielding joint (1.4-137 to 1.4-146): no cohesion, no tensile strength, and a
// dilation that follows from the apparent friction, so those keys do not apply.
void readContinuouslyYielding(TableReader& r, JointMaterial& j) {
  for (const char* key : {"cohesion", "tension", "dilation"})
    if (r.has(key))
      r.fail(key, "does not apply to the continuously-yielding law (no cohesion or tensile strength; its dilation "
                  "follows from the apparent friction, 1.4-145)");
  const double friction = r.number("friction");
  if (!(friction > 0.0 && friction < 90.0)) r.fail("friction", "must be in (0, 90) degrees, got " + shown(friction));
  const double initial = r.number("initial_friction", friction);
  if (!(initial >= friction && initial < 90.0))
    r.fail("initial_friction", "must be in [friction, 90) degrees (" + shown(friction) + " to 90), got " + shown(initial));
  j.friction = radians(friction);
  j.initialFriction = radians(initial);
  j.tanFriction = std::tan(j.friction);
  j.roughness = r.positive("roughness");
  auto stiffnessLaw = [&r](const char* coefficientKey, const char* exponentKey, double& coefficient, double& exponent) {
    if (!r.has(coefficientKey)) {
      if (r.has(exponentKey)) r.fail(exponentKey, std::string("needs ") + coefficientKey);
      return;
    }
    coefficient = r.positive(coefficientKey);
    exponent = r.number(exponentKey, 0.0);
    if (!(exponent >= 0.0 && exponent <= 1.0)) r.fail(exponentKey, "must be in [0, 1], got " + shown(exponent));
  };
  stiffnessLaw("kn_coefficient", "kn_exponent", j.knCoefficient, j.knExponent);
  stiffnessLaw("ks_coefficient", "ks_exponent", j.ksCoefficient, j.ksExponent);
}

void addBlock(Model& m, const BlockInput& in) {
  const double area = signedArea(in.polygon);
  const Vec2 c = centroid(in.polygon);
  const double density = m.blockMaterials[in.material].density;
  checkMassProperties(m, in.where, in.material, area, density * area, density * polarSecondMoment(in.polygon));
  Blocks& b = m.blocks;
  b.name.push_back(in.name);
  b.material.push_back(in.material);
  b.firstVertex.push_back(m.vertices.size());
  b.vertexCount.push_back(static_cast<int>(in.polygon.size()));
  b.mass.push_back(density * area);
  b.inertia.push_back(density * polarSecondMoment(in.polygon));
  b.driven.push_back(in.driven);
  double radius = 0.0;
  for (const Vec2& p : in.polygon) radius = std::max(radius, norm(p - c));
  b.boundingRadius.push_back(radius);
  b.initialCentroid.push_back(c);
  b.centroid.push_back(c);
  b.rotation.push_back(0.0);
  b.velocity.push_back(in.velocity);
  b.angularVelocity.push_back(in.angularVelocity);
  b.force.push_back({});
  b.moment.push_back(0.0);
  b.appliedForce.push_back(in.force);
  b.appliedMoment.push_back(in.moment);
  b.deformable.push_back(0);
  b.velocityHistory.push_back(in.velocityHistory);
  b.inputVelocity.push_back(in.velocity);
  b.inputAngularVelocity.push_back(in.angularVelocity);
  const int block = b.size() - 1;
  for (const Vec2& p : in.polygon) {
    m.vertices.block.push_back(block);
    m.vertices.localPosition.push_back(p - c);
    m.vertices.geometry.push_back({p, {}, {}, 0.0, 0.0});
  }
}

}  // namespace

// SHA-256 of the scene as parsed (overrides applied) with its first k phases, k = 0 .. n: a
// restart may append phases, but what ran before the save must be what the scene says.
static std::vector<std::string> phasePrefixHashes(const toml::table& root) {
  const toml::array* phases = root["phase"].as_array();
  const std::size_t n = phases ? phases->size() : 0;
  std::vector<std::string> hashes;
  for (std::size_t k = 0; k <= n; ++k) {
    toml::table copy = root;
    if (phases) {
      toml::array kept;
      for (std::size_t i = 0; i < k; ++i) kept.push_back(*phases->get(i));
      copy.insert_or_assign("phase", std::move(kept));
    }
    std::ostringstream text;
    text << toml::toml_formatter(copy);
    hashes.push_back(sha256Hex(text.str()));
  }
  return hashes;
}

// The region of an [[excavation]] or [[phase.excavation]]: circle = { centre, radius } or a
// convex polygon.
static ExcavationRegion readRegion(TableReader& r) {
  ExcavationRegion region;
  region.where = r.location();
  if (r.has("circle") == r.has("polygon")) r.failTable("give either circle = { centre, radius } or polygon = [...]");
  if (r.has("circle")) {
    auto c = r.subtable("circle");
    if (!c) r.fail("circle", "must be a table { centre = [x, y], radius = R }");
    region.centre = c->vec2("centre");
    region.radius = c->positive("radius");
    c->finish();
  } else {
    region.polygon = r.polygon("polygon");
    validateBlockPolygon(region.polygon, 0.0, r.location());
  }
  return region;
}

static StopCriteria readStop(TableReader& t) {
  StopCriteria s;
  if (t.has("cycles")) {
    s.cycles = t.integer("cycles");
    if (s.cycles <= 0) t.fail("cycles", "must be > 0");
  }
  if (t.has("time")) s.time = t.positive("time");
  if (t.has("ratio")) s.ratio = t.positive("ratio");
  if (s.cycles < 0 && s.time < 0 && s.ratio < 0) t.failTable("set at least one of cycles, time or ratio");
  if (s.ratio > 0 && s.cycles < 0 && s.time < 0)
    t.fail("ratio", "needs a limit as well: set cycles or time, so that a run that never reaches the ratio ends");
  t.finish();
  return s;
}

// `geometry` is the model as the phase will find it (excavated by the phases before), on which
// its boundaries select gridpoints and edges; `m` receives their time functions.
static Phase readPhase(TableReader& r, Model& m, std::vector<std::string>& warnings, std::optional<Model>& geometry,
                       std::set<std::string>& activeBoundaries,
                       const std::function<int(TableReader&, std::string_view, const std::string&)>& blockIndex) {
  Phase phase;
  phase.name = r.string("name");
  auto stop = r.subtable("stop");
  if (!stop) r.fail("stop", "is required: each phase sets stop = { cycles, time or ratio }");
  phase.stop = readStop(*stop);
  phase.requireEquilibrium = r.boolean("require_equilibrium", false);
  if (phase.requireEquilibrium && phase.stop.ratio < 0)
    r.fail("require_equilibrium", "needs stop.ratio: equilibrium is the unbalanced-force ratio falling to it");
  PhaseChanges& c = phase.changes;
  if (r.has("gravity")) c.gravity = r.vec2("gravity");
  if (r.has("mass_damping") && r.has("adaptive_damping"))
    r.fail("mass_damping", "give mass_damping or adaptive_damping, not both");
  if (r.has("mass_damping")) c.massDamping = r.nonNegative("mass_damping", 0.0);
  if (r.has("adaptive_damping")) c.adaptiveDamping = r.boolean("adaptive_damping", false);
  for (const std::string& what : r.has("reset") ? r.strings("reset") : std::vector<std::string>{}) {
    if (what == "displacements") c.resetDisplacements = true;
    else if (what == "velocities") c.resetVelocities = true;
    else r.fail("reset", "unknown item '" + what + "'; use \"displacements\" and/or \"velocities\"");
  }
  for (auto [table, prefix] : r.tables("joint_material")) {
    TableReader jr(*table, prefix, r.file());
    const std::string name = jr.string("name");
    JointStrengthChange change;
    for (std::size_t i = 0; i < m.jointMaterials.size(); ++i)
      if (m.jointMaterials[i].name == name) change.material = static_cast<int>(i);
    if (change.material < 0) jr.fail("name", "no joint material named '" + name + "'");
    const JointMaterial& j = m.jointMaterials[change.material];
    if (j.law == JointLaw::ContinuouslyYielding)
      jr.fail("name", "joint material '" + name + "' is continuously yielding; a phase changes the friction, cohesion "
                      "and tension of the Coulomb and point-contact laws only");
    if (jr.has("friction")) change.tanFriction = std::tan(radians(jr.angleDegrees("friction", 0.0)));
    if (jr.has("cohesion")) change.cohesion = jr.nonNegative("cohesion", 0.0);
    if (jr.has("tension")) change.tension = jr.nonNegative("tension", 0.0);
    if (j.law == JointLaw::PointContact && (change.cohesion.value_or(0.0) > 0 || change.tension.value_or(0.0) > 0))
      jr.fail(change.cohesion.value_or(0.0) > 0 ? "cohesion" : "tension",
              "the point-contact law has no cohesion or tensile strength");
    jr.finish();
    if (!change.tanFriction && !change.cohesion && !change.tension)
      jr.failTable("changes nothing: give friction, cohesion and/or tension");
    c.joints.push_back(change);
  }
  for (const std::string& name : r.has("free") ? r.strings("free") : std::vector<std::string>{}) {
    if (!activeBoundaries.erase(name))
      r.fail("free", "no boundary named '" + name + "' is active when the phase starts (give [[boundary]] or an "
                     "earlier phase's [[phase.boundary]] that name)");
    c.freeBoundaries.push_back(name);
  }
  for (auto [table, prefix] : r.tables("block_material")) {
    TableReader br(*table, prefix, r.file());
    const std::string name = br.string("name");
    int material = -1;
    for (std::size_t i = 0; i < m.blockMaterials.size(); ++i)
      if (m.blockMaterials[i].name == name) material = static_cast<int>(i);
    if (material < 0) br.fail("name", "no block material named '" + name + "'");
    BlockMaterial changed = m.blockMaterials[material];
    changed.plastic = false;
    readPlasticity(br, changed, warnings);
    br.finish();
    if (!changed.plastic)
      br.failTable("changes nothing: give the Mohr-Coulomb strength, friction and cohesion (and dilation, tension)");
    c.blockStrengths.emplace_back(material, changed.mohrCoulomb);
  }
  for (auto [table, prefix] : r.tables("block")) {
    TableReader br(*table, prefix, r.file());
    RigidBlockChange change;
    change.block = blockIndex(br, "name", br.string("name"));
    if (m.blocks.deformable[change.block])
      br.fail("name", "block '" + m.blocks.name[change.block] + "' is deformable: a phase holds, drives and loads its "
                      "gridpoints through [[phase.boundary]] tables");
    auto dofs = [&](const char* key) {
      std::uint8_t bits = 0;
      for (const std::string& dof : br.has(key) ? br.strings(key) : std::vector<std::string>{}) {
        const std::uint8_t bit = dof == "x" ? DriveX : dof == "y" ? DriveY : dof == "rotation" ? DriveRotation : 0;
        if (!bit) br.fail(key, "unknown degree of freedom '" + dof + "'; use \"x\", \"y\" or \"rotation\"");
        bits |= bit;
      }
      return bits;
    };
    change.fix = dofs("fix");
    change.free = dofs("free");
    if (change.fix & change.free) br.fail("free", "a degree of freedom is both fixed and freed");
    if (br.has("velocity") && !(change.fix & (DriveX | DriveY)))
      br.fail("velocity", "drives the components given in fix (\"x\", \"y\"); add them to fix");
    if (br.has("angular_velocity") && !(change.fix & DriveRotation))
      br.fail("angular_velocity", "drives the rotation: add \"rotation\" to fix");
    change.velocity = br.vec2("velocity", {0.0, 0.0});
    change.angularVelocity = br.number("angular_velocity", 0.0);
    if (br.has("force")) change.force = br.vec2("force");
    if (br.has("moment")) change.moment = br.number("moment");
    br.finish();
    if (!change.fix && !change.free && !change.force && !change.moment)
      br.failTable("changes nothing: give fix, free, force and/or moment");
    c.blocks.push_back(change);
  }
  for (auto [table, prefix] : r.tables("excavation")) {
    TableReader er(*table, prefix, r.file());
    ExcavationRegion region = readRegion(er);
    for (int b = 0; b < m.blocks.size(); ++b)
      if (!m.blocks.deformable[b] && region.contains(m.blocks.centroid[b]))
        er.failTable("holds the centroid of rigid block '" + m.blocks.name[b] + "': a phase excavates zones of "
                     "deformable blocks only; remove rigid blocks before the run with [[excavation]]");
    if (!geometry) geometry = m;
    if (excavateZones(*geometry, [&](Vec2 p) { return region.contains(p); }, region.where).removed == 0)
      er.failTable("removes nothing: no zone centroid lies in it when the phase starts");
    if (geometry->zones.size() == 0) er.failTable("removes every zone: the model would have none left");
    er.finish();
    c.excavations.push_back(std::move(region));
  }
  for (auto [table, prefix] : r.tables("boundary")) {
    TableReader br(*table, prefix, r.file());
    Model& selected = geometry ? *geometry : m;
    BoundaryCondition condition = readBoundary(br, selected, r.file(), blockIndex);
    if (geometry) m.timeFunctions = geometry->timeFunctions;
    if (!condition.name.empty() && !activeBoundaries.insert(condition.name).second)
      br.fail("name", "boundary '" + condition.name + "' is active when the phase starts; free it first with this "
                      "phase's free = [\"" + condition.name + "\"]");
    c.boundaries.push_back(std::move(condition));
  }
  r.finish();
  return phase;
}

Scene readScene(const std::string& path, const std::vector<std::string>& overrides) {
  std::ifstream stream(path, std::ios::binary);
  if (!stream) throw SceneError(path + ": cannot open the scene file");
  std::stringstream buffer;
  buffer << stream.rdbuf();
  const std::string bytes = buffer.str();

  Scene scene;
  scene.path = path;
  scene.sha256 = sha256Hex(bytes);
  scene.overrides = overrides;
  toml::table root;
  try {
    root = toml::parse(bytes, path);
  } catch (const toml::parse_error& e) {
    std::ostringstream s;
    s << path << ":" << e.source().begin.line << ": " << e.description();
    throw SceneError(s.str());
  }
  for (const std::string& o : overrides) applyOverride(root, o);
  scene.phasePrefixSha256 = phasePrefixHashes(root);

  TableReader top(root, "", path);
  Model& m = scene.model;
  scene.title = top.string("title", "");

  // [model]
  {
    auto t = top.subtable("model");
    if (!t) top.fail("model", "is required: the [model] table sets at least the rounding length");
    m.gravity = t->vec2("gravity", {0.0, 0.0});
    m.roundingLength = t->positive("rounding");
    m.contactTolerance = t->has("contact_tolerance") ? t->positive("contact_tolerance") : m.roundingLength;
    std::string defaultJoint = t->string("default_joint", "");
    // materials are read below; resolve the default afterwards
    for (auto [table, prefix] : top.tables("block_material")) {
      TableReader r(*table, prefix, path);
      BlockMaterial mat;
      mat.name = r.string("name");
      mat.density = r.positive("density");
      readElasticConstants(r, mat);
      readPlasticity(r, mat, scene.warnings);
      for (const auto& other : m.blockMaterials)
        if (other.name == mat.name) r.fail("name", "block material '" + mat.name + "' is defined twice");
      m.blockMaterials.push_back(mat);
      r.finish();
    }
    for (auto [table, prefix] : top.tables("joint_material")) {
      TableReader r(*table, prefix, path);
      JointMaterial j;
      j.name = r.string("name");
      for (const auto& other : m.jointMaterials)
        if (other.name == j.name) r.fail("name", "joint material '" + j.name + "' is defined twice");
      const std::string law = r.string("law", "coulomb-slip");
      if (law == "coulomb-slip") j.law = JointLaw::CoulombSlip;
      else if (law == "coulomb-fracture") j.law = JointLaw::CoulombFracture;
      else if (law == "point-contact") j.law = JointLaw::PointContact;
      else if (law == "continuously-yielding") j.law = JointLaw::ContinuouslyYielding;
      else r.fail("law", "unknown joint law '" + law +
                             "'; use coulomb-slip, coulomb-fracture, continuously-yielding or point-contact");
      j.kn = r.positive("kn");
      j.ks = r.positive("ks");
      if (j.law == JointLaw::ContinuouslyYielding) {
        readContinuouslyYielding(r, j);
        m.jointMaterials.push_back(j);
        r.finish();
        continue;
      }
      const double friction = r.angleDegrees("friction", 0.0);
      const double dilation = r.angleDegrees("dilation", 0.0);
      j.tanFriction = std::tan(radians(friction));
      j.tanDilation = std::tan(radians(dilation));
      j.cohesion = r.nonNegative("cohesion", 0.0);
      j.tension = r.nonNegative("tension", 0.0);
      if (j.law == JointLaw::PointContact && (j.cohesion > 0 || j.tension > 0))
        r.fail(j.cohesion > 0 ? "cohesion" : "tension", "the point-contact law has no cohesion or tensile strength");
      m.jointMaterials.push_back(j);
      r.finish();
    }
    if (defaultJoint.empty()) {
      if (m.jointMaterials.size() > 1)
        t->fail("default_joint", "is required when more than one joint material is defined");
      m.defaultJoint = m.jointMaterials.empty() ? -1 : 0;
    } else {
      for (std::size_t i = 0; i < m.jointMaterials.size(); ++i)
        if (m.jointMaterials[i].name == defaultJoint) m.defaultJoint = static_cast<int>(i);
      if (m.defaultJoint < 0) t->fail("default_joint", "no joint material named '" + defaultJoint + "'");
    }
    t->finish();
  }
  auto materialIndex = [&](TableReader& r) {
    const std::string name = r.string("material");
    for (std::size_t i = 0; i < m.blockMaterials.size(); ++i)
      if (m.blockMaterials[i].name == name) return static_cast<int>(i);
    r.fail("material", "no block material named '" + name + "'");
  };

  // [solver] and [stop]
  if (auto t = top.subtable("solver")) {
    scene.settings.frac = t->number("frac", 0.1);
    if (!(scene.settings.frac > 0 && scene.settings.frac <= 10))
      t->fail("frac", "must be in (0, 10], got " + shown(scene.settings.frac));
    scene.settings.zoneFraction = t->number("zone_fraction", 1.0);
    if (!(scene.settings.zoneFraction > 0 && scene.settings.zoneFraction <= 10))
      t->fail("zone_fraction", "must be in (0, 10], got " + shown(scene.settings.zoneFraction));
    scene.settings.massDamping = t->nonNegative("mass_damping", 0.0);
    scene.settings.adaptiveDamping = t->boolean("adaptive_damping", false);
    if (t->has("local_damping")) {
      scene.settings.localDamping = t->number("local_damping");
      if (!(scene.settings.localDamping > 0.0 && scene.settings.localDamping < 1.0))
        t->fail("local_damping", "must lie in (0, 1): the fraction of each out-of-balance force turned against the motion "
                                 "(0.8 is the usual value)");
      if (t->has("mass_damping") || scene.settings.adaptiveDamping)
        t->fail("local_damping", "replaces mass damping; give local_damping or mass_damping / adaptive_damping, not both");
    }
    if (scene.settings.adaptiveDamping && t->has("mass_damping"))
      t->fail("mass_damping", "adaptive_damping sets the mass damping itself; give one or the other");
    if (t->has("stiffness_damping") && t->has("rayleigh"))
      t->fail("rayleigh", "sets the stiffness damping itself; give rayleigh or stiffness_damping, not both");
    if (t->has("stiffness_damping")) scene.settings.stiffnessDamping = t->nonNegative("stiffness_damping", 0.0);
    if (t->has("rayleigh")) {
      if (t->has("mass_damping"))
        t->fail("rayleigh", "sets the mass damping itself; give rayleigh, or mass_damping with stiffness_damping");
      auto ray = t->subtable("rayleigh");
      if (!ray) t->fail("rayleigh", "must be a table { ratio = XI, frequency = F }");
      const double ratio = ray->number("ratio"), frequency = ray->positive("frequency");
      if (!(ratio > 0.0 && ratio < 1.0)) ray->fail("ratio", "must be in (0, 1): the critical-damping ratio at the frequency");
      ray->finish();
      // xi(w) = (alpha / w + beta w) / 2 is smallest, xi, at w_min = 2 pi f (1.3-18, 1.3-19).
      const double w = 2.0 * std::numbers::pi * frequency;
      scene.settings.massDamping = ratio * w;
      scene.settings.stiffnessDamping = ratio / w;
    }
    if (scene.settings.stiffnessDamping > 0.0 && (scene.settings.adaptiveDamping || t->has("local_damping")))
      t->fail(t->has("rayleigh") ? "rayleigh" : "stiffness_damping",
              "goes with mass damping (Rayleigh damping), not with adaptive or local damping");
    scene.settings.densityScaling = t->boolean("density_scaling", false);
    scene.settings.staticSolve = t->boolean("static_solve", false);
    t->finish();
  }
  if (top.has("phase")) {
    if (top.has("stop"))
      top.fail("stop", "with [[phase]] tables each phase has its own stop; move [stop] into the phases and remove it");
  } else {
    auto t = top.subtable("stop");
    if (!t) top.fail("stop", "is required: set [stop] cycles, time or ratio (or give [[phase]] tables, each with its stop)");
    scene.settings.stop = readStop(*t);
  }

  if (auto t = top.subtable("output")) {
    if (t->has("vtk_every")) {
      const long long every = t->integer("vtk_every");
      if (every < 1) t->fail("vtk_every", "must be >= 1 (cycles between VTK snapshots)");
      scene.settings.snapshotEvery = every;
    }
    t->finish();
  }

  // Blocks, explicit and cut from regions, in input order.
  std::vector<BlockInput> inputs;
  std::map<std::string, std::string> nameOrigin;
  auto claimName = [&](TableReader& r, const std::string& name, const std::string& origin) {
    auto [it, fresh] = nameOrigin.emplace(name, origin);
    if (!fresh) r.fail("name", "block name '" + name + "' is already used by " + it->second);
  };
  SetupProgress progress;
  std::size_t zonesSoFar = 0;
  for (auto [table, prefix] : top.tables("block")) {
    TableReader r(*table, prefix, path);
    BlockInput in;
    in.name = r.string("name");
    claimName(r, in.name, prefix);
    in.material = materialIndex(r);
    in.mesh = readZoning(r, [&] { return r.polygon("vertices"); }, zonesSoFar, progress);
    if (in.mesh) zonesSoFar += in.mesh->triangles.size();
    if (in.mesh) {
      if (!m.blockMaterials[in.material].elastic())
        r.fail("material", "a deformable block needs an elastic material: give block material '" +
                               m.blockMaterials[in.material].name + "' young and poisson (or bulk and shear)");
      for (const char* key : {"fix", "velocity", "angular_velocity", "force", "moment"})
        if (r.has(key))
          r.fail(key, "a deformable block is loaded and held through [[boundary]] tables, not block keys");
      in.where = path + ": block '" + in.name + "' (" + prefix + ")";
      r.finish();
      inputs.push_back(in);
      continue;
    }
    in.polygon = r.polygon("vertices");
    if (r.has("fix")) {
      for (const std::string& dof : r.strings("fix")) {
        const std::uint8_t bit = dof == "x" ? DriveX : dof == "y" ? DriveY : dof == "rotation" ? DriveRotation : 0;
        if (!bit) r.fail("fix", "unknown degree of freedom '" + dof + "'; use \"x\", \"y\" or \"rotation\"");
        in.driven |= bit;
      }
    }
    in.velocity = r.vec2("velocity", {0.0, 0.0});
    in.angularVelocity = r.number("angular_velocity", 0.0);
    in.force = r.vec2("force", {0.0, 0.0});
    in.moment = r.number("moment", 0.0);
    if (r.has("velocity_history")) {
      if (!in.driven)
        r.fail("velocity_history", "scales the velocity of fixed degrees of freedom, and block '" + in.name +
                                       "' has none: add fix = [\"x\"] (or y, rotation)");
      m.timeFunctions.push_back(readHistory(r, path, "velocity_history"));
      in.velocityHistory = static_cast<int>(m.timeFunctions.size()) - 1;
    }
    in.where = path + ": block '" + in.name + "' (" + prefix + ", line " + std::to_string(table->source().begin.line) + ")";
    r.finish();
    inputs.push_back(in);
  }
  for (auto [table, prefix] : top.tables("region")) {
    TableReader r(*table, prefix, path);
    RegionSpec region;
    region.name = r.string("name");
    const int material = materialIndex(r);
    region.boundary = r.polygon("vertices");
    validateBlockPolygon(region.boundary, 0.0, path + ": region '" + region.name + "' (" + prefix + ")");
    if (r.has("seed")) {
      const long long seed = r.integer("seed");
      if (seed < 0) r.fail("seed", "must be >= 0");
      region.seed = static_cast<std::uint64_t>(seed);
    }
    for (auto [ct, cp] : r.tables("crack")) {
      TableReader c(*ct, cp, path);
      region.cracks.push_back({c.vec2("from"), c.vec2("to")});
      c.finish();
    }
    for (auto [jt, jp] : r.tables("joint_set")) {
      TableReader j(*jt, jp, path);
      JointSetSpec s;
      s.angleDeg = j.number("angle");
      // A direction: beyond a turn either way the number only loses the digits that place it.
      if (!(std::abs(s.angleDeg) <= 360.0)) j.fail("angle", "must be in [-360, 360] degrees, got " + shown(s.angleDeg));
      s.angleVariationDeg = j.nonNegative("angle_variation", 0.0);
      if (!(s.angleVariationDeg <= 90.0))
        j.fail("angle_variation", "must be in [0, 90] degrees, got " + shown(s.angleVariationDeg));
      s.spacing = j.positive("spacing");
      s.spacingVariation = j.nonNegative("spacing_variation", 0.0);
      if (s.spacingVariation >= s.spacing) j.fail("spacing_variation", "must be less than spacing");
      s.trace = j.has("trace") ? j.positive("trace") : 0.0;
      s.traceVariation = j.nonNegative("trace_variation", 0.0);
      if (s.traceVariation > 0 && s.traceVariation >= s.trace) j.fail("trace_variation", "must be less than trace (and trace must be set)");
      s.gap = j.nonNegative("gap", 0.0);
      s.gapVariation = j.nonNegative("gap_variation", 0.0);
      if (s.gapVariation > s.gap) j.fail("gap_variation", "must not exceed gap");
      if (s.gap > 0 && s.trace <= 0) j.fail("gap", "a gap needs a finite trace length");
      s.origin = j.vec2("origin", {0.0, 0.0});
      region.jointSets.push_back(s);
      j.finish();
    }
    r.finish();
    // Bounded before any cut: a spacing of 1e-9 or a tiny trace once ran for minutes.
    const RegionEstimate estimate = estimateRegion(region);
    const double left = static_cast<double>(kSceneBlockLimit) - static_cast<double>(inputs.size());
    if (estimate.blocks > left)
      r.fail(region.jointSets.empty() ? "crack" : "joint_set",
             "region '" + region.name + "' would be cut into up to " + shownCount(estimate.blocks) +
                 " blocks (1 + cracks + joint lines + crossings of lines of different sets, the lines counted at "
                 "spacing - spacing_variation), more than the " + shownCount(left) + " left of the scene's limit of " +
                 std::to_string(kSceneBlockLimit) + " blocks: raise the spacing of its joint sets");
    if (estimate.segments > kRegionSegmentLimit)
      r.fail("joint_set", "region '" + region.name + "' would be cut with up to " + shownCount(estimate.segments) +
                              " joint segments (per joint line, its longest chord over the shortest trace + gap), "
                              "more than the limit of " + shownCount(kRegionSegmentLimit) + ": raise trace or gap");
    const std::string cutting = "cutting region '" + region.name + "' into up to " + shownCount(estimate.blocks) + " blocks: ";
    progress.show(cutting + "0", estimate.blocks > 1e5);
    const std::vector<Polygon> pieces =
        cutRegion(region, [&](std::size_t blocks) { progress.show(cutting + std::to_string(blocks)); });
    for (std::size_t k = 0; k < pieces.size(); ++k) {
      BlockInput in;
      in.name = region.name + "." + std::to_string(k + 1);
      claimName(r, in.name, prefix);
      in.material = material;
      in.polygon = pieces[k];
      in.where = path + ": block '" + in.name + "' cut from region '" + region.name + "' (" + prefix + ")";
      inputs.push_back(in);
    }
  }
  if (inputs.empty()) top.fail("block", "the scene has no blocks: add [[block]] or [[region]]");
  // Excavation: rigid blocks whose centroid lies in the region go, and so do the zones of
  // deformable blocks whose centroid does (the outline then follows the zones left).
  for (auto [table, prefix] : top.tables("excavation")) {
    TableReader r(*table, prefix, path);
    const ExcavationRegion region = readRegion(r);
    const auto inside = [&region](Vec2 p) { return region.contains(p); };
    std::size_t removed = 0;
    std::vector<BlockInput> kept;
    for (BlockInput& in : inputs) {
      if (in.mesh) {
        const std::size_t before = in.mesh->triangles.size();
        in.mesh = withoutTriangles(*in.mesh, inside);
        removed += before - in.mesh->triangles.size();
        if (in.mesh->triangles.empty()) continue;
      } else if (inside(centroid(in.polygon))) {
        ++removed;
        continue;
      }
      kept.push_back(std::move(in));
    }
    if (removed == 0) r.failTable("removes nothing: no block centroid and no zone centroid lies in it");
    if (kept.empty()) r.failTable("removes every block: the scene would be empty");
    inputs = std::move(kept);
    r.finish();
  }
  for (const BlockInput& in : inputs) {
    if (in.mesh) {
      addDeformableBlock(m, in.name, in.material, *in.mesh);
      continue;
    }
    validateBlockPolygon(in.polygon, m.roundingLength, in.where);
    addBlock(m, in);
  }
  if (scene.settings.stiffnessDamping > 0.0) {
    auto solver = top.subtable("solver");
    const char* key = solver->has("rayleigh") ? "rayleigh" : "stiffness_damping";
    for (int b = 0; b < m.blocks.size(); ++b)
      if (m.blocks.deformable[b])
        solver->fail(key, "acts on the joints between rigid blocks; block '" + m.blocks.name[b] +
                              "' is deformable, and the zones' viscous stress is not implemented");
    for (const JointMaterial& j : m.jointMaterials)
      if (j.law == JointLaw::ContinuouslyYielding)
        solver->fail(key, "damps linear joint springs; joint material '" + j.name + "' is continuously yielding");
  }
  // A weight beyond the range of a double would first show as a NaN energy, blamed on the step.
  for (int b = 0; b < m.blocks.size(); ++b)
    if (!std::isfinite(m.blocks.mass[b] * norm(m.gravity)))
      top.subtable("model")->fail("gravity", "its magnitude times the mass of block '" + m.blocks.name[b] + "' (" +
                                                 shown(m.blocks.mass[b]) + " kg/m) is beyond the range of a double: "
                                                 "lower model.gravity or the block's density");
  bool anyRigid = false;
  for (int b = 0; b < m.blocks.size(); ++b) anyRigid = anyRigid || !m.blocks.deformable[b];
  if (m.jointMaterials.empty() && (m.blocks.size() > 1 || anyRigid))
    top.fail("joint_material", "at least one [[joint_material]] is required when the scene has more than one block or a "
                               "rigid block (the rigid-block time step, 1.3-28, takes the joint stiffness)");
  if (m.blocks.size() > 1) attachDeformableOutlines(m);
  computeBoundaryGeometry(m);
  for (int b = 0; b < m.blocks.size(); ++b) placeBlockVertices(m, b);

  auto blockIndex = [&](TableReader& r, std::string_view key, const std::string& name) {
    for (int b = 0; b < m.blocks.size(); ++b)
      if (m.blocks.name[b] == name) return b;
    r.fail(key, "no block named '" + name + "'");
  };
  readBoundaries(top, m, path, blockIndex);
  // Phases after the boundaries: a phase's boundary conditions select the model's gridpoints,
  // and may free only conditions active when the phase starts.
  std::set<std::string> activeBoundaries;
  for (const BoundaryCondition& b : m.boundaryConditions)
    if (!b.name.empty()) activeBoundaries.insert(b.name);
  std::optional<Model> excavated;  // a copy of the model, excavated as the phases will, once one does
  for (auto [table, prefix] : top.tables("phase")) {
    TableReader r(*table, prefix, path);
    scene.settings.phases.push_back(readPhase(r, m, scene.warnings, excavated, activeBoundaries, blockIndex));
    for (std::size_t i = 0; i + 1 < scene.settings.phases.size(); ++i)
      if (scene.settings.phases[i].name == scene.settings.phases.back().name)
        r.fail("name", "phase '" + scene.settings.phases[i].name + "' is defined twice");
  }
  readInitialStress(top, m);
  for (auto [table, prefix] : top.tables("joint_assignment")) {
    TableReader r(*table, prefix, path);
    const auto names = r.strings("blocks");
    if (names.size() != 2) r.fail("blocks", "must name exactly two blocks");
    const int a = blockIndex(r, "blocks", names[0]), b = blockIndex(r, "blocks", names[1]);
    const std::string joint = r.string("joint");
    int index = -1;
    for (std::size_t i = 0; i < m.jointMaterials.size(); ++i)
      if (m.jointMaterials[i].name == joint) index = static_cast<int>(i);
    if (index < 0) r.fail("joint", "no joint material named '" + joint + "'");
    const std::pair<int, int> pair{std::min(a, b), std::max(a, b)};
    if (a == b) r.fail("blocks", "a joint is between two different blocks");
    for (const auto& [assigned, material] : m.jointAssignments)
      if (assigned == pair)
        r.fail("blocks", "the joint between '" + names[0] + "' and '" + names[1] + "' is already assigned ('" +
                             m.jointMaterials[material].name + "')");
    m.jointAssignments.push_back({pair, index});
    r.finish();
  }

  std::set<std::string> historyNames;
  for (auto [table, prefix] : top.tables("history")) {
    TableReader r(*table, prefix, path);
    HistorySpec h;
    h.name = r.string("name");
    if (!historyNames.insert(h.name).second) r.fail("name", "history '" + h.name + "' is defined twice");
    const std::string quantity = r.string("quantity");
    const auto info = findHistoryQuantity(quantity);
    if (!info) {
      std::string known;
      for (const auto& q : historyQuantities()) known += (known.empty() ? "" : ", ") + std::string(q.name);
      r.fail("quantity", "unknown quantity '" + quantity + "'; known: " + known);
    }
    h.quantity = info->quantity;
    const bool zoneMean = h.quantity == HistoryQuantity::MeanSxx || h.quantity == HistoryQuantity::MeanSyy ||
                          h.quantity == HistoryQuantity::MeanSxy;
    if (zoneMean && m.zones.size() == 0)
      r.fail("quantity", quantity + " averages the stress of the zones, and the scene has no deformable block");
    if (info->subject == HistorySubject::Block) {
      h.block = blockIndex(r, "block", r.string("block"));
      if (m.blocks.deformable[h.block])
        r.fail("block", "block '" + m.blocks.name[h.block] + "' is deformable: its motion is its gridpoints'; use "
                        "gridpoint.* or zone.* quantities with a point");
    } else if (info->subject == HistorySubject::Joint) {
      const auto names = r.strings("blocks");
      if (names.size() != 2) r.fail("blocks", "a joint history names exactly two blocks");
      h.block = blockIndex(r, "blocks", names[0]);
      h.otherBlock = blockIndex(r, "blocks", names[1]);
      if (h.block == h.otherBlock) r.fail("blocks", "a joint is between two different blocks");
    } else if (info->subject == HistorySubject::Gridpoint || info->subject == HistorySubject::Zone) {
      h.block = blockIndex(r, "block", r.string("block"));
      if (!m.blocks.deformable[h.block])
        r.fail("block", "block '" + m.blocks.name[h.block] + "' is rigid: " + std::string(info->name) +
                            " needs a deformable block; use block.* quantities for a rigid block");
      const Vec2 point = r.vec2("point");
      if (info->subject == HistorySubject::Gridpoint) h.gridpoint = nearestGridpoint(m, h.block, point);
      else h.zone = zoneAt(m, h.block, point);
      if (h.gridpoint < 0 && h.zone < 0)
        r.fail("point", "is not inside block '" + m.blocks.name[h.block] + "': a zone history samples the zone that holds the point");
    }
    if (r.has("every")) h.every = static_cast<int>(r.integer("every", 1, std::numeric_limits<int>::max()));
    // A zone a phase will excavate (at the positions the scene gives) cannot be sampled after it.
    if (h.zone >= 0) {
      const auto& n = m.zones.gridpoint[h.zone];
      const Vec2 c = (1.0 / 3.0) * (m.gridpoints.position[n[0]] + m.gridpoints.position[n[1]] + m.gridpoints.position[n[2]]);
      for (const Phase& phase : scene.settings.phases)
        for (const ExcavationRegion& region : phase.changes.excavations)
          if (region.contains(c))
            r.fail("point", "lies in a zone that " + region.where + " of phase '" + phase.name +
                                "' excavates; give the history a point in a zone that stays");
    }
    r.finish();
    scene.histories.push_back(h);
  }
  top.finish();
  return scene;
}

}  // namespace vdec
