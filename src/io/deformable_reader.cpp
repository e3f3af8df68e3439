#include "io/deformable_reader.hpp"

#include "boundary/boundary_conditions.hpp"

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <cmath>
#include <numbers>

#include "core/errors.hpp"

namespace vdec {

void readPlasticity(TableReader& r, BlockMaterial& mat, std::vector<std::string>& warnings) {
  if (!r.has("friction") && !r.has("cohesion") && !r.has("dilation") && !r.has("tension")) return;
  if (!mat.elastic())
    r.fail(r.has("friction") ? "friction" : r.has("cohesion") ? "cohesion" : r.has("dilation") ? "dilation" : "tension",
           "Mohr-Coulomb plasticity needs the elastic constants too (young and poisson, or bulk and shear)");
  const double friction = r.number("friction");
  if (!(friction > 0.0 && friction < 90.0)) r.fail("friction", "must be in (0, 90) degrees, got " + shown(friction));
  const double cohesion = r.number("cohesion");
  if (cohesion < 0.0) r.fail("cohesion", "must be >= 0, got " + shown(cohesion));
  const double dilation = r.number("dilation", 0.0);
  if (!(dilation >= 0.0 && dilation < 90.0)) r.fail("dilation", "must be in [0, 90) degrees, got " + shown(dilation));
  const double phi = radians(friction), psi = radians(dilation);
  MohrCoulombProperties& mc = mat.mohrCoulomb;
  mc.nPhi = (1.0 + std::sin(phi)) / (1.0 - std::sin(phi));
  mc.nPsi = (1.0 + std::sin(psi)) / (1.0 - std::sin(psi));
  mc.cohesion = cohesion;
  // Without a cut-off the tensile strength is the apex of the Mohr-Coulomb cone, c / tan(phi).
  const double apex = cohesion / std::tan(phi);
  if (!std::isfinite(apex))
    r.fail("friction", shown(friction) + " degrees with a cohesion of " + shown(cohesion) +
                           " Pa puts the cone's apex c / tan(phi) at infinity; give a larger friction angle");
  mc.tension = r.has("tension") ? r.nonNegative("tension", 0.0) : apex;
  if (mc.tension > apex) r.fail("tension", "must not exceed the cone's apex c / tan(phi) = " + shown(apex) + " Pa");
  mat.plastic = true;
  // 1.4.6.9: a dilation above the friction angle with no cohesion creates energy.
  if (dilation > friction && cohesion == 0.0)
    warnings.push_back(r.location() + ": dilation " + shown(dilation) + " degrees exceeds friction " + shown(friction) +
                       " degrees with zero cohesion: plastic flow then generates energy (1.4.6.9)");
}

void readElasticConstants(TableReader& r, BlockMaterial& mat) {
  const bool young = r.has("young") || r.has("poisson");
  const bool bulk = r.has("bulk") || r.has("shear");
  if (young && bulk) r.fail(r.has("bulk") ? "bulk" : "shear", "give either young and poisson, or bulk and shear");
  if (young) {
    const double E = r.positive("young");
    const double nu = r.number("poisson");
    if (!(nu > -1.0 && nu < 0.5)) r.fail("poisson", "must be in (-1, 0.5), got " + shown(nu));
    mat.bulk = E / (3.0 * (1.0 - 2.0 * nu));
    mat.shear = E / (2.0 * (1.0 + nu));
  } else if (bulk) {
    mat.bulk = r.positive("bulk");
    mat.shear = r.positive("shear");
  }
  if (young && !(std::isfinite(mat.bulk) && std::isfinite(mat.shear)))
    r.fail("young", "with poisson " + shown(r.number("poisson")) + " gives a bulk modulus of " + shown(mat.bulk) +
                        " Pa, beyond the range of a double: lower young");
}

namespace {

int positiveCount(TableReader& r, std::string_view key, int limit) { return static_cast<int>(r.integer(key, 1, limit)); }

}  // namespace

namespace {

// Refuses a zoning that would take the scene past kSceneZoneLimit, before it is built; shows a
// progress line for a large one.
void checkZoneCount(TableReader& r, std::string_view key, double zones, const std::string& how,
                    std::size_t zonesBefore, SetupProgress& progress) {
  const double left = static_cast<double>(kSceneZoneLimit) - static_cast<double>(zonesBefore);
  if (zones > left)
    r.fail(key, "makes " + how + " = " + shownCount(zones) + " zones, more than the " + shownCount(left) +
                    " left of the scene's limit of " + std::to_string(kSceneZoneLimit) + " zones (" +
                    std::to_string(zonesBefore) + " in the blocks before it): zone it more coarsely");
  if (zones > 2e5) progress.show("zoning " + r.location() + ": about " + shownCount(zones) + " zones", true);
}

}  // namespace

std::optional<Mesh> readZoning(TableReader& r, const std::function<Polygon()>& vertices, std::size_t zonesBefore,
                               SetupProgress& progress) {
  if (r.has("annulus")) {
    if (r.has("vertices")) r.fail("vertices", "an annulus block takes its outline from `annulus`; remove `vertices`");
    if (r.has("zoning")) r.fail("zoning", "an annulus block is zoned by its `annulus` table; remove `zoning`");
    auto t = r.subtable("annulus");
    if (!t) r.fail("annulus", "must be a table");
    AnnulusSpec s;
    s.centre = t->vec2("centre", {0.0, 0.0});
    s.inner = t->positive("inner");
    s.outer = t->positive("outer");
    if (s.outer <= s.inner) t->fail("outer", "must be larger than inner");
    const double from = t->number("from", 0.0), to = t->number("to", 90.0);
    if (!(to > from && to - from <= 360.0)) t->fail("to", "must be above `from` by at most 360 degrees");
    if (to - from >= 360.0) t->fail("to", "a full ring is not one block: use two half rings or less");
    s.angle0 = from * std::numbers::pi / 180.0;
    s.angle1 = to * std::numbers::pi / 180.0;
    s.radial = positiveCount(*t, "radial", 4096);
    s.circumferential = positiveCount(*t, "circumferential", 4096);
    s.grading = t->number("grading", 1.0);
    if (!(s.grading >= 0.2 && s.grading <= 5.0)) t->fail("grading", "must be in [0.2, 5], got " + shown(s.grading));
    t->finish();
    checkZoneCount(r, "annulus", 4.0 * s.radial * s.circumferential, "4 radial circumferential", zonesBefore, progress);
    return crossedAnnulusMesh(s);
  }
  if (!r.has("zoning")) return std::nullopt;
  auto t = r.subtable("zoning");
  if (!t) r.fail("zoning", "must be a table, e.g. zoning = { nx = 8, ny = 4 }");
  const Polygon p = vertices();
  if (t->has("max_edge")) {
    // Unstructured: any convex polygon, quality triangles no longer than max_edge.
    const double maxEdge = t->positive("max_edge");
    if (t->has("nx") || t->has("ny")) t->fail("max_edge", "give either max_edge (unstructured) or nx and ny (structured)");
    validateBlockPolygon(p, 0.0, r.location());
    double perimeter = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) perimeter += norm(p[(i + 1) % p.size()] - p[i]);
    if (perimeter / maxEdge > 1e5) t->fail("max_edge", "is too small for this block: over 1e5 edges on its outline");
    checkZoneCount(*t, "max_edge", kDelaunayZonesPerArea * signedArea(p) / (maxEdge * maxEdge),
                   "about 6 area / max_edge^2", zonesBefore, progress);
    t->finish();
    return delaunayMesh(p, maxEdge);
  }
  if (p.size() != 4) r.fail("zoning", "structured zoning needs a quadrilateral block (4 vertices), got " + std::to_string(p.size()));
  // Convex and counter-clockwise, like every block (edge lengths do not matter without contacts).
  validateBlockPolygon(p, 0.0, r.location());
  const int nx = positiveCount(*t, "nx", 4096), ny = positiveCount(*t, "ny", 4096);
  t->finish();
  checkZoneCount(r, "zoning", 4.0 * nx * ny, "4 nx ny", zonesBefore, progress);
  return crossedQuadMesh({p[0], p[1], p[2], p[3]}, nx, ny);
}

void checkMassProperties(const Model& m, const std::string& where, int material, double area, double mass,
                         double inertia) {
  const BlockMaterial& mat = m.blockMaterials[material];
  const std::string density = "block_material[" + std::to_string(material) + "].density";
  if (!(std::isfinite(area) && area > 0.0))
    throw SceneError(where + ": its area, " + shown(area) + " m^2, is not a finite positive number: the coordinates "
                     "of its vertices are too large; give them in m, below about 1e150");
  if (!(std::isfinite(mass) && mass > 0.0))
    throw SceneError(where + ": its mass, " + density + " (" + shown(mat.density) + " kg/m^3) times its area (" +
                     shown(area) + " m^2), is " + shown(mass) + " kg/m, not a finite positive number: lower " + density);
  if (!(std::isfinite(inertia) && inertia >= 0.0))
    throw SceneError(where + ": its moment of inertia, " + density + " (" + shown(mat.density) +
                     " kg/m^3) times the polar second moment of its area, is " + shown(inertia) +
                     " kg m, not a finite number: lower " + density + " or the size of the block");
}

void addDeformableBlock(Model& m, const std::string& name, int material, const Mesh& mesh) {
  Blocks& b = m.blocks;
  const int block = b.size();
  const double density = m.blockMaterials[material].density;
  double area = 0.0;
  Vec2 moment;
  for (const auto& t : mesh.triangles) {
    const Vec2 p0 = mesh.nodes[t[0]], p1 = mesh.nodes[t[1]], p2 = mesh.nodes[t[2]];
    const double a = 0.5 * cross(p1 - p0, p2 - p0);
    area += a;
    moment += (a / 3.0) * (p0 + p1 + p2);
  }
  checkMassProperties(m, "block '" + name + "'", material, area, density * area, 0.0);
  const Vec2 c = (1.0 / area) * moment;
  b.name.push_back(name);
  b.material.push_back(material);
  b.firstVertex.push_back(m.vertices.size());
  b.vertexCount.push_back(0);  // its outline becomes its vertices in attachDeformableOutlines
  b.mass.push_back(density * area);
  b.inertia.push_back(0.0);
  b.driven.push_back(0);
  double radius = 0.0;
  for (const Vec2& p : mesh.nodes) radius = std::max(radius, norm(p - c));
  b.boundingRadius.push_back(radius);
  b.initialCentroid.push_back(c);
  b.centroid.push_back(c);
  b.rotation.push_back(0.0);
  b.velocity.push_back({});
  b.angularVelocity.push_back(0.0);
  b.force.push_back({});
  b.moment.push_back(0.0);
  b.appliedForce.push_back({});
  b.appliedMoment.push_back(0.0);
  b.deformable.push_back(1);
  b.velocityHistory.push_back(-1);
  b.inputVelocity.push_back({});
  b.inputAngularVelocity.push_back(0.0);

  Gridpoints& g = m.gridpoints;
  const int first = g.size();
  for (const Vec2& p : mesh.nodes) {
    g.block.push_back(block);
    g.initialPosition.push_back(p);
    g.position.push_back(p);
    g.velocity.push_back({});
    g.tractionForce.push_back({});
    g.driven.push_back(0);
  }
  Zones& z = m.zones;
  for (const auto& t : mesh.triangles) {
    z.gridpoint.push_back({first + t[0], first + t[1], first + t[2]});
    z.block.push_back(block);
    z.material.push_back(material);
    z.sxx.push_back(0.0);
    z.syy.push_back(0.0);
    z.sxy.push_back(0.0);
    z.szz.push_back(0.0);
    z.plasticState.push_back(Elastic);
  }
  for (const auto& [from, to] : boundaryEdges(mesh)) m.boundaryEdges.push_back({block, first + from, first + to});
  const MeshQuality q = meshQuality(mesh);
  if (q.minAngleDegrees < 1.0)
    throw GeometryError("block '" + name + "': zone " + std::to_string(q.worstTriangle) + " is a sliver (smallest angle " +
                        shown(q.minAngleDegrees) + " degrees); change the zoning (nx, ny, radial, circumferential, grading)");
}

namespace {

std::array<double, 3> triple(TableReader& r, std::string_view key) {
  const std::vector<double> v = r.numbers(key, 3, "must be an array of three numbers [sxx, syy, sxy]");
  return {v[0], v[1], v[2]};
}

std::array<double, 4> quadruple(TableReader& r, std::string_view key) {
  const std::vector<double> v = r.numbers(key, 4, "must be an array of four numbers [sxx, syy, sxy, szz]");
  return {v[0], v[1], v[2], v[3]};
}

// A closed range [lo, hi] on a coordinate, or everything.
struct Range {
  double lo = -INFINITY, hi = INFINITY;
  bool holds(double v, double slack) const { return v >= lo - slack && v <= hi + slack; }
};

Range readRange(TableReader& r, std::string_view key) {
  if (!r.has(key)) return {};
  const Vec2 v = r.vec2(key);
  if (v.y < v.x) r.fail(key, "must be [low, high] with low <= high");
  return {v.x, v.y};
}

// A boundary stress given along a boundary as a table of polar angle (degrees, about the
// boundary's centre) against sxx, syy, sxy, read from a CSV file beside the scene: for far-field
// values that no constant-plus-gradient stress describes (an exact solution on a truncated
// domain). Values between rows are interpolated linearly.
struct StressTable {
  std::vector<double> angle;
  std::vector<std::array<double, 3>> stress;
  std::string file;

  std::array<double, 3> at(double a, TableReader& r) const {
    if (a < angle.front() - 1e-9 || a > angle.back() + 1e-9)
      r.fail("stress_table", file + " covers angles " + shown(angle.front()) + " to " + shown(angle.back()) +
                                 " degrees, not the edge at " + shown(a) + " degrees");
    const auto it = std::upper_bound(angle.begin(), angle.end(), a);
    const std::size_t k = std::clamp<std::size_t>(static_cast<std::size_t>(it - angle.begin()), 1, angle.size() - 1);
    const double w = (a - angle[k - 1]) / (angle[k] - angle[k - 1]);
    std::array<double, 3> out{};
    for (int i = 0; i < 3; ++i) out[i] = (1.0 - w) * stress[k - 1][i] + w * stress[k][i];
    return out;
  }
};

// The fields of one line of a CSV table (commas or spaces between them).
std::vector<std::string_view> csvFields(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ',' || std::isspace(static_cast<unsigned char>(line[i])))) ++i;
    const std::size_t begin = i;
    while (i < line.size() && line[i] != ',' && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i > begin) fields.push_back(line.substr(begin, i - begin));
  }
  return fields;
}

// A whole field as a number; from_chars also reads nan and inf, so that such rows are refused
// as rows rather than skipped as headers.
std::optional<double> csvNumber(std::string_view field) {
  if (!field.empty() && field[0] == '+') field.remove_prefix(1);
  double v = 0.0;
  const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), v);
  if (end != field.data() + field.size()) return std::nullopt;
  if (error == std::errc::result_out_of_range) return INFINITY;
  if (error != std::errc()) return std::nullopt;
  return v;
}

// Rows of `columns` numbers from a CSV file beside the scene (named by `key` of `r`): a header
// line (its first field a word, not nan or inf) and '#' comments are skipped, every value must be finite,
// the first column must increase, two rows at least. The file must be a regular file of at most
// kTableFileBytes and kTableRows rows, checked before it is read, so that a path to a device or
// an endless file is an error and not a hang. Errors name the table's key, the file and the line.
std::vector<std::vector<double>> readColumns(TableReader& r, std::string_view key, const std::string& scenePath,
                                             const std::string& columns, std::size_t count, std::string& file) {
  file = (std::filesystem::path(scenePath).parent_path() / r.string(key)).string();
  std::error_code error;
  const auto status = std::filesystem::status(file, error);
  if (!error && std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
    r.fail(key, "'" + file + "' is not a regular file (a device, pipe or directory): give a CSV file");
  const std::uintmax_t bytes = std::filesystem::file_size(file, error);
  if (!error && bytes > kTableFileBytes)
    r.fail(key, "'" + file + "' has " + std::to_string(bytes) + " bytes, more than the limit of " +
                    std::to_string(kTableFileBytes) + " for a table file: thin the table");
  std::ifstream in(file);
  if (!in) r.fail(key, "cannot open '" + file + "'");
  std::vector<std::vector<double>> rows;
  std::string line;
  std::uintmax_t read = 0;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    read += line.size() + 1;
    if (read > kTableFileBytes)  // the file grew while it was read
      r.fail(key, file + ":" + std::to_string(number) + ": more than " + std::to_string(kTableFileBytes) + " bytes");
    const std::vector<std::string_view> fields = csvFields(line);
    if (fields.empty() || fields[0][0] == '#') continue;
    if (std::isalpha(static_cast<unsigned char>(fields[0][0])) && !csvNumber(fields[0])) continue;  // header
    const std::string at = file + ":" + std::to_string(number) + ": ";
    if (fields.size() != count) r.fail(key, at + "expected " + std::to_string(count) + " numbers: " + columns);
    std::vector<double> row;
    for (std::string_view field : fields) {
      const std::optional<double> v = csvNumber(field);
      if (!v) r.fail(key, at + "expected " + std::to_string(count) + " numbers: " + columns);
      if (!std::isfinite(*v)) r.fail(key, at + "'" + std::string(field) + "' is not a finite number");
      row.push_back(*v);
    }
    if (!rows.empty() && !(row[0] > rows.back()[0])) r.fail(key, at + "the first column must increase");
    if (rows.size() == kTableRows)
      r.fail(key, at + "more than " + std::to_string(kTableRows) + " rows, the limit for a table file: thin the table");
    rows.push_back(std::move(row));
  }
  if (rows.size() < 2) r.fail(key, file + ": needs at least two rows");
  return rows;
}

StressTable readStressTable(TableReader& r, const std::string& scenePath) {
  StressTable t;
  for (const auto& row : readColumns(r, "stress_table", scenePath, "angle_deg, sxx, syy, sxy", 4, t.file)) {
    t.angle.push_back(row[0]);
    t.stress.push_back({row[1], row[2], row[3]});
  }
  return t;
}

}  // namespace

TimeFunction readHistory(TableReader& r, const std::string& scenePath, std::string_view key) {
  auto t = r.subtable(key);
  if (!t) r.fail(key, "must be a table, e.g. " + std::string(key) + " = { kind = \"sine\", frequency = 10.0 }");
  TimeFunction f;
  const std::string kind = t->string("kind");
  if (kind == "constant") {
    f.kind = TimeFunction::Kind::Constant;
  } else if (kind == "linear") {
    f.kind = TimeFunction::Kind::Linear;
    f.start = t->number("start", 0.0);
    f.rate = t->number("rate");
  } else if (kind == "sine" || kind == "cosine") {
    f.kind = kind == "sine" ? TimeFunction::Kind::Sine : TimeFunction::Kind::Cosine;
    f.frequency = t->positive("frequency");
    f.phase = t->number("phase", 0.0);
  } else if (kind == "table") {
    f.kind = TimeFunction::Kind::Table;
    for (const auto& row : readColumns(*t, "file", scenePath, "t, f", 2, f.name)) {
      f.t.push_back(row[0]);
      f.f.push_back(row[1]);
    }
  } else {
    t->fail("kind", "unknown history '" + kind + "'; use constant, linear, sine, cosine or table");
  }
  t->finish();
  return f;
}

BoundaryCondition readBoundary(TableReader& r, Model& m, const std::string& path,
                               const std::function<int(TableReader&, std::string_view, const std::string&)>& blockIndex) {
  {
    BoundaryCondition condition;
    condition.name = r.string("name", "");
    const int block = blockIndex(r, "block", r.string("block"));
    if (!m.blocks.deformable[block])
      r.fail("block", "block '" + m.blocks.name[block] + "' is rigid: [[boundary]] applies to deformable blocks; "
                      "give a rigid block `fix`, `velocity` or `force` in its [[block]] table");
    // Which gridpoints: the ranges on their initial position, all optional.
    const Range xr = readRange(r, "x"), yr = readRange(r, "y"), rr = readRange(r, "r");
    Range angle = readRange(r, "angle");
    const Vec2 centre = r.vec2("centre", {0.0, 0.0});
    if (!r.has("r") && !r.has("angle") && !r.has("stress_table") && r.has("centre"))
      r.fail("centre", "is used only with r, angle or stress_table");
    // Selection slack: round-off of the generated coordinates, relative to the block's size.
    const double slack = 1e-9 * std::max(1.0, 2.0 * m.blocks.boundingRadius[block]);
    std::vector<char> selected(m.gridpoints.size(), 0);
    int count = 0;
    for (int i = 0; i < m.gridpoints.size(); ++i) {
      if (m.gridpoints.block[i] != block) continue;
      const Vec2 p = m.gridpoints.initialPosition[i];
      const Vec2 d = p - centre;
      const double theta = std::atan2(d.y, d.x) * 180.0 / std::numbers::pi;
      const bool in = xr.holds(p.x, slack) && yr.holds(p.y, slack) && rr.holds(norm(d), slack) &&
                      angle.holds(theta, 1e-7);
      if (in) {
        selected[i] = 1;
        ++count;
      }
    }
    if (count == 0) r.failTable("selects no gridpoint of block '" + m.blocks.name[block] + "': check x, y, r, angle");

    if (r.boolean("viscous", false)) {
      for (const char* key : {"fix", "velocity_x", "velocity_y", "stress", "pressure", "stress_table", "history",
                              "stress_gradient_x", "stress_gradient_y"})
        if (r.has(key))
          r.fail(key, "a viscous boundary only absorbs; give fixities, velocities and stresses in other tables");
      const BlockMaterial& mat = m.blockMaterials[m.blocks.material[block]];
      for (const Model::BoundaryEdge& be : m.boundaryEdges)
        if (be.block == block && selected[be.from] && selected[be.to])
          condition.dashpots.push_back({be.from, be.to, std::sqrt(mat.density * (mat.bulk + 4.0 * mat.shear / 3.0)),
                                        std::sqrt(mat.density * mat.shear), -1});
      if (condition.dashpots.empty())
        r.failTable("selects no boundary edge of block '" + m.blocks.name[block] +
                    "': dashpots act on edges of the block's outline whose two ends are both selected");
      r.finish();
      return condition;
    }
    const bool fix = r.has("fix"), vx = r.has("velocity_x"), vy = r.has("velocity_y");
    const bool tabulated = r.has("stress_table");
    const bool stress = r.has("stress") || tabulated, pressure = r.has("pressure");
    if (tabulated && r.has("stress")) r.fail("stress_table", "give either stress or stress_table");
    if (!(fix || vx || vy || stress || pressure))
      r.failTable("sets nothing: give fix, velocity_x, velocity_y, stress, pressure or viscous = true");
    if ((fix || vx || vy) && (stress || pressure))
      r.failTable("a boundary either drives gridpoints (fix, velocity) or loads edges (stress, pressure); use two tables");
    if (stress && pressure) r.fail("pressure", "give either stress or pressure");
    int history = -1;
    if (r.has("history")) {
      if (!(vx || vy || stress || pressure))
        r.fail("history", "a fixed gridpoint has no value to vary: a history scales a velocity, stress or pressure");
      m.timeFunctions.push_back(readHistory(r, path, "history"));
      history = static_cast<int>(m.timeFunctions.size()) - 1;
    }
    condition.history = history;

    if (fix || vx || vy) {
      std::uint8_t bits = 0;
      if (fix)
        for (const std::string& dof : r.strings("fix")) {
          const std::uint8_t bit = dof == "x" ? DriveX : dof == "y" ? DriveY : 0;
          if (!bit) r.fail("fix", "unknown component '" + dof + "'; use \"x\" or \"y\"");
          bits |= bit;
        }
      const double ux = vx ? r.number("velocity_x") : 0.0, uy = vy ? r.number("velocity_y") : 0.0;
      if ((vx && (bits & DriveX)) || (vy && (bits & DriveY)))
        r.fail("fix", "a component is both fixed and given a velocity");
      condition.fix = bits;
      condition.velocityBits = static_cast<std::uint8_t>((vx ? DriveX : 0) | (vy ? DriveY : 0));
      condition.velocity = {ux, uy};
      for (int i = 0; i < m.gridpoints.size(); ++i)
        if (selected[i]) condition.gridpoints.push_back(i);
    } else {
      std::array<double, 3> s{}, gx{}, gy{};
      StressTable stressTable;
      if (pressure) {
        const double p = r.number("pressure");
        s = {-p, -p, 0.0};
      } else if (tabulated) {
        if (r.has("stress_gradient_x") || r.has("stress_gradient_y"))
          r.fail("stress_table", "a stress table sets the stress along the boundary; it takes no gradients");
        stressTable = readStressTable(r, path);
      } else {
        s = triple(r, "stress");
      }
      if (r.has("stress_gradient_x")) gx = triple(r, "stress_gradient_x");
      if (r.has("stress_gradient_y")) gy = triple(r, "stress_gradient_y");
      int edges = 0;
      for (const Model::BoundaryEdge& be : m.boundaryEdges) {
        if (be.block != block) continue;
        {
          const int from = be.from, to = be.to;
          if (!selected[from] || !selected[to]) continue;
          const Vec2 mid = 0.5 * (m.gridpoints.initialPosition[from] + m.gridpoints.initialPosition[to]);
          LoadedEdge e;
          e.from = from;
          e.to = to;
          e.history = history;
          if (tabulated) {
            const Vec2 d = mid - centre;
            const std::array<double, 3> v = stressTable.at(std::atan2(d.y, d.x) * 180.0 / std::numbers::pi, r);
            e.sxx = v[0];
            e.syy = v[1];
            e.sxy = v[2];
          } else {
            e.sxx = s[0] + gx[0] * mid.x + gy[0] * mid.y;
            e.syy = s[1] + gx[1] * mid.x + gy[1] * mid.y;
            e.sxy = s[2] + gx[2] * mid.x + gy[2] * mid.y;
          }
          condition.edges.push_back(e);
          ++edges;
        }
      }
      if (edges == 0)
        r.failTable("selects no boundary edge of block '" + m.blocks.name[block] +
                    "': stress and pressure act on edges of the block's outline whose two ends are both selected");
    }
    r.finish();
    return condition;
  }
}

void readBoundaries(TableReader& top, Model& m, const std::string& path,
                    const std::function<int(TableReader&, std::string_view, const std::string&)>& blockIndex) {
  for (auto [table, prefix] : top.tables("boundary")) {
    TableReader r(*table, prefix, path);
    BoundaryCondition condition = readBoundary(r, m, path, blockIndex);
    for (const BoundaryCondition& other : m.boundaryConditions)
      if (!condition.name.empty() && other.name == condition.name)
        r.fail("name", "boundary '" + condition.name + "' is defined twice");
    addBoundaryCondition(m, std::move(condition), 0.0);
  }
}

int nearestGridpoint(const Model& m, int block, Vec2 point) {
  int best = -1;
  double bestDistance = INFINITY;
  for (int i = 0; i < m.gridpoints.size(); ++i) {
    if (m.gridpoints.block[i] != block) continue;
    const double d = norm(m.gridpoints.initialPosition[i] - point);
    if (d < bestDistance) {
      bestDistance = d;
      best = i;
    }
  }
  return best;
}

int zoneAt(const Model& m, int block, Vec2 point) {
  const Gridpoints& g = m.gridpoints;
  for (int z = 0; z < m.zones.size(); ++z) {
    if (m.zones.block[z] != block) continue;
    const auto& n = m.zones.gridpoint[z];
    const Vec2 p0 = g.initialPosition[n[0]], p1 = g.initialPosition[n[1]], p2 = g.initialPosition[n[2]];
    const double scale = 1e-12 * cross(p1 - p0, p2 - p0);
    // Inside or on the boundary (the first zone in id order wins a shared edge).
    if (cross(p1 - p0, point - p0) >= -scale && cross(p2 - p1, point - p1) >= -scale &&
        cross(p0 - p2, point - p2) >= -scale)
      return z;
  }
  return -1;
}

void readInitialStress(TableReader& top, Model& m) {
  auto t = top.subtable("initial_stress");
  if (!t) return;
  const double sxx = t->number("sxx", 0.0), syy = t->number("syy", 0.0), sxy = t->number("sxy", 0.0),
               szz = t->number("szz", 0.0);
  std::array<double, 4> gx{}, gy{};
  if (t->has("gradient_x")) gx = quadruple(*t, "gradient_x");
  if (t->has("gradient_y")) gy = quadruple(*t, "gradient_y");
  if (m.zones.size() == 0) t->failTable("needs deformable blocks: it sets the stress of zones");
  for (int z = 0; z < m.zones.size(); ++z) {
    const auto& n = m.zones.gridpoint[z];
    const Vec2 c = (1.0 / 3.0) * (m.gridpoints.position[n[0]] + m.gridpoints.position[n[1]] + m.gridpoints.position[n[2]]);
    m.zones.sxx[z] = sxx + gx[0] * c.x + gy[0] * c.y;
    m.zones.syy[z] = syy + gx[1] * c.x + gy[1] * c.y;
    m.zones.sxy[z] = sxy + gx[2] * c.x + gy[2] * c.y;
    m.zones.szz[z] = szz + gx[3] * c.x + gy[3] * c.y;
  }
  t->finish();
}

}  // namespace vdec
