// [[boundary]] tables, the time functions and CSV tables they use, and [initial_stress].
#include <charconv>
#include <filesystem>
#include <fstream>

#include "core/shown.hpp"
#include "io/scene_sections.hpp"

namespace vdec {

namespace {

std::array<double, 3> triple(TableReader& r, std::string_view key) {
  const std::vector<double> v = r.numbers(key, 3, "must be an array of three numbers [sxx, syy, sxy]");
  return {v[0], v[1], v[2]};
}

std::array<double, 4> quadruple(TableReader& r, std::string_view key) {
  const std::vector<double> v = r.numbers(key, 4, "must be an array of four numbers [sxx, syy, sxy, szz]");
  return {v[0], v[1], v[2], v[3]};
}

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

// Rows of `count` numbers from a CSV file beside the scene (named by `key` of `r`): a header
// line (its first field a word, not nan or inf) and '#' comments are skipped, every value must
// be finite, the first column must increase, two rows at least. The file must be a regular file
// of at most kTableFileBytes and kTableRows rows, checked before it is read, so that a path to a
// device or an endless file is an error and not a hang. Errors name the table's key, the file
// and the line.
std::vector<std::vector<double>> readColumns(TableReader& r, std::string_view key, const std::string& columns,
                                             std::size_t count, std::string& file) {
  file = (std::filesystem::path(r.file()).parent_path() / r.string(key)).string();
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

// A boundary stress given along a boundary as a table of polar angle (degrees, about the
// boundary's centre) against sxx, syy, sxy, read from a CSV file beside the scene: for far-field
// values that no constant-plus-gradient stress describes (an exact solution on a truncated
// domain). Values between rows are interpolated linearly.
StressTable readStressTable(TableReader& r) {
  StressTable t;
  for (const auto& row : readColumns(r, "stress_table", "angle_deg, sxx, syy, sxy", 4, t.file)) {
    t.angle.push_back(row[0]);
    t.stress.push_back({row[1], row[2], row[3]});
  }
  return t;
}

}  // namespace

CoordinateRange readRange(TableReader& r, std::string_view key) {
  if (!r.has(key)) return {};
  const Vec2 v = r.vec2(key);
  if (v.y < v.x) r.fail(key, "must be [low, high] with low <= high");
  return {v.x, v.y};
}


TimeFunction readTimeFunction(TableReader& r, std::string_view key) {
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
    for (const auto& row : readColumns(*t, "file", "t, f", 2, f.name)) {
      f.t.push_back(row[0]);
      f.f.push_back(row[1]);
    }
    if (t->boolean("integrate", false)) f.integrate();
  } else {
    t->fail("kind", "unknown history '" + kind + "'; use constant, linear, sine, cosine or table");
  }
  t->finish();
  return f;
}

BoundaryDefinition readBoundary(TableReader& r) {
  BoundaryDefinition d;
  d.origin = r.origin();
  d.name = r.string("name", "");
  d.freeField = r.boolean("free_field", false);
  d.block = d.freeField ? r.string("block", "") : r.string("block");
  readSelection(r, d);
  if (!r.has("r") && !r.has("angle") && !r.has("stress_table") && r.has("centre"))
    r.fail("centre", "is used only with r, angle or stress_table");
  const bool viscous = r.boolean("viscous", false);
  if (viscous && d.freeField) r.fail("free_field", "a free-field boundary has dashpots of its own: drop viscous = true");
  if (viscous || d.freeField) {
    for (const char* key : {"fix", "velocity_x", "velocity_y", "stress", "pressure", "stress_table",
                            "stress_gradient_x", "stress_gradient_y"})
      if (r.has(key))
        r.fail(key, std::string(viscous ? "a viscous boundary absorbs, and takes an incoming wave as input_velocity"
                                        : "a free-field boundary applies the free field's motion and stress") +
                        "; give fixities, velocities and stresses in other tables");
    d.viscous = viscous;
    if (d.freeField && !r.has("x"))
      r.fail("free_field", "needs x = [x0, x0]: the vertical side beside which the column runs");
    d.material = r.string("material", "");
    if (r.has("material") && d.material.empty()) r.fail("material", "is empty: name a [[block_material]], or leave the key out for the block's own");
    if (r.has("input_velocity")) d.inputVelocity = r.vec2("input_velocity");
    if (r.has("history")) {
      if (!r.has("input_velocity")) r.fail("history", "scales the input_velocity; give input_velocity");
      d.history = readTimeFunction(r, "history");
    }
    return d;
  }
  if (r.has("material")) r.fail("material", "is the medium beyond a viscous or free-field boundary: it needs viscous = true or free_field = true");
  if (r.has("input_velocity"))
    r.fail("input_velocity", "is the incoming wave of a viscous or free-field boundary: it needs viscous = true or free_field = true");
  const bool fix = r.has("fix"), vx = r.has("velocity_x"), vy = r.has("velocity_y");
  const bool tabulated = r.has("stress_table");
  const bool stress = r.has("stress") || tabulated, pressure = r.has("pressure");
  if (tabulated && r.has("stress")) r.fail("stress_table", "give either stress or stress_table");
  if (!(fix || vx || vy || stress || pressure))
    r.failTable("sets nothing: give fix, velocity_x, velocity_y, stress, pressure, viscous = true or free_field = true");
  if ((fix || vx || vy) && (stress || pressure))
    r.failTable("a boundary either drives gridpoints (fix, velocity) or loads edges (stress, pressure); use two tables");
  if (stress && pressure) r.fail("pressure", "give either stress or pressure");
  if (r.has("history")) {
    if (!(vx || vy || stress || pressure))
      r.fail("history", "a fixed gridpoint has no value to vary: a history scales a velocity, stress or pressure");
    d.history = readTimeFunction(r, "history");
  }
  if (fix || vx || vy) {
    if (fix)
      for (const std::string& dof : r.strings("fix")) {
        const std::uint8_t bit = dof == "x" ? DriveX : dof == "y" ? DriveY : 0;
        if (!bit) r.fail("fix", "unknown component '" + dof + "'; use \"x\" or \"y\"");
        d.fix |= bit;
      }
    d.velocity = {vx ? r.number("velocity_x") : 0.0, vy ? r.number("velocity_y") : 0.0};
    if ((vx && (d.fix & DriveX)) || (vy && (d.fix & DriveY))) r.fail("fix", "a component is both fixed and given a velocity");
    d.velocityBits = static_cast<std::uint8_t>((vx ? DriveX : 0) | (vy ? DriveY : 0));
    return d;
  }
  d.loaded = true;
  if (pressure) {
    const double p = r.number("pressure");
    d.stress = {-p, -p, 0.0};
  } else if (tabulated) {
    if (r.has("stress_gradient_x") || r.has("stress_gradient_y"))
      r.fail("stress_table", "a stress table sets the stress along the boundary; it takes no gradients");
    d.stressTable = readStressTable(r);
  } else {
    d.stress = triple(r, "stress");
  }
  if (r.has("stress_gradient_x")) d.gradientX = triple(r, "stress_gradient_x");
  if (r.has("stress_gradient_y")) d.gradientY = triple(r, "stress_gradient_y");
  return d;
}

BoundaryElementsDefinition readBoundaryElements(TableReader& t) {
  BoundaryElementsDefinition d;
  d.origin = t.origin();
  d.young = t.positive("young");
  d.poisson = t.number("poisson");
  if (!(d.poisson >= 0.0 && d.poisson < 0.5)) t.fail("poisson", "must lie in [0, 0.5), got " + shown(d.poisson));
  d.halfPlane = t.boolean("half_plane", false);
  if (d.halfPlane) d.surfaceY = t.number("surface_y");
  else if (t.has("surface_y")) t.fail("surface_y", "is the free surface of a half-plane: give half_plane = true, or remove it");
  d.block = t.string("block", "");
  readSelection(t, d);
  t.finish();
  return d;
}

void readBoundaries(TableReader& top, SceneDefinition& scene) {
  for (auto [table, prefix] : top.tables("boundary")) {
    TableReader r(*table, prefix, top.file());
    scene.boundaries.push_back(readBoundary(r));
    r.finish();
  }
  if (auto t = top.subtable("boundary_elements")) scene.boundaryElements = readBoundaryElements(*t);
  for (auto [table, prefix] : top.tables("initial_wave")) {
    TableReader r(*table, prefix, top.file());
    InitialWaveDefinition d;
    d.origin = r.origin();
    const std::string kind = r.string("kind");
    if (kind != "P" && kind != "S") r.fail("kind", "unknown wave '" + kind + "'; use \"P\" or \"S\"");
    d.shear = kind == "S";
    d.directionDegrees = r.number("direction");
    d.centre = r.vec2("centre");
    d.amplitude = r.number("amplitude");
    d.width = r.positive("width");
    d.frontWidth = r.has("front_width") ? r.positive("front_width") : INFINITY;
    d.block = r.string("block", "");
    r.finish();
    scene.initialWaves.push_back(d);
  }
  auto t = top.subtable("initial_stress");
  if (!t) return;
  InitialStressDefinition d;
  d.origin = t->origin();
  d.stress = {t->number("sxx", 0.0), t->number("syy", 0.0), t->number("sxy", 0.0), t->number("szz", 0.0)};
  if (t->has("gradient_x")) d.gradientX = quadruple(*t, "gradient_x");
  if (t->has("gradient_y")) d.gradientY = quadruple(*t, "gradient_y");
  t->finish();
  scene.initialStress = d;
}

}  // namespace vdec
