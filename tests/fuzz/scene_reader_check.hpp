#pragma once
// The oracle of the scene-reader fuzz target and of its regression replay: what readScene may
// do with any bytes at all. It may throw one of vdec's documented errors (exit codes 2 to 7),
// or return a scene whose every number is finite and whose counts are in range; anything else
// (another exception, which the command line turns into exit code 1, or a non-finite number
// that the run would carry into its results) is a defect. Sanitizer findings and signals are
// caught by the build around it (scripts/fuzz.sh, scripts/sanitize.sh).
#include <cmath>
#include <exception>
#include <string>

#include "core/errors.hpp"
#include "io/scene_reader.hpp"

namespace vdec::fuzz {

class FiniteCheck {
 public:
  // The first offence found, "" when none.
  const std::string& defect() const { return defect_; }

  void number(double v, const std::string& what) {
    if (defect_.empty() && !std::isfinite(v)) defect_ = what + " is not finite (" + std::to_string(v) + ")";
  }
  void point(Vec2 p, const std::string& what) {
    number(p.x, what + ".x");
    number(p.y, what + ".y");
  }
  void positive(double v, const std::string& what) {
    number(v, what);
    if (defect_.empty() && !(v > 0.0)) defect_ = what + " is not > 0 (" + std::to_string(v) + ")";
  }
  void atLeastOne(long long v, const std::string& what) {
    if (defect_.empty() && v < 1) defect_ = what + " is below 1 (" + std::to_string(v) + ")";
  }

 private:
  std::string defect_;
};

inline std::string modelDefect(const Scene& scene) {
  const Model& m = scene.model;
  FiniteCheck c;
  c.point(m.gravity, "model.gravity");
  c.positive(m.roundingLength, "model.rounding");
  c.positive(m.contactTolerance, "model.contact_tolerance");
  for (const BlockMaterial& b : m.blockMaterials) {
    const std::string at = "block material '" + b.name + "' ";
    c.positive(b.density, at + "density");
    c.number(b.bulk, at + "bulk modulus");
    c.number(b.shear, at + "shear modulus");
    c.number(b.mohrCoulomb.nPhi, at + "N_phi");
    c.number(b.mohrCoulomb.nPsi, at + "N_psi");
    c.number(b.mohrCoulomb.cohesion, at + "cohesion");
    c.number(b.mohrCoulomb.tension, at + "tension");
  }
  for (const JointMaterial& j : m.jointMaterials) {
    const std::string at = "joint material '" + j.name + "' ";
    c.positive(j.kn, at + "kn");
    c.positive(j.ks, at + "ks");
    for (double v : {j.tanFriction, j.cohesion, j.tension, j.tanDilation, j.knCoefficient, j.knExponent,
                     j.ksCoefficient, j.ksExponent, j.friction, j.initialFriction, j.roughness})
      c.number(v, at + "property");
  }
  const Blocks& b = m.blocks;
  for (int i = 0; i < b.size(); ++i) {
    const std::string at = "block '" + b.name[i] + "' ";
    c.positive(b.mass[i], at + "mass");
    c.number(b.inertia[i], at + "moment of inertia");
    c.number(b.boundingRadius[i], at + "bounding radius");
    c.point(b.centroid[i], at + "centroid");
    c.point(b.velocity[i], at + "velocity");
    c.number(b.angularVelocity[i], at + "angular velocity");
    c.point(b.appliedForce[i], at + "force");
    c.number(b.appliedMoment[i], at + "moment");
  }
  for (int v = 0; v < m.vertices.size(); ++v) {
    c.point(m.vertices.geometry[v].position, "vertex " + std::to_string(v) + " position");
    c.point(m.vertices.geometry[v].arcCentre, "vertex " + std::to_string(v) + " arc centre");
    c.number(m.vertices.geometry[v].arcRadius, "vertex " + std::to_string(v) + " arc radius");
  }
  for (int g = 0; g < m.gridpoints.size(); ++g) {
    c.point(m.gridpoints.position[g], "gridpoint " + std::to_string(g) + " position");
    c.point(m.gridpoints.velocity[g], "gridpoint " + std::to_string(g) + " velocity");
  }
  for (int z = 0; z < m.zones.size(); ++z)
    for (double s : {m.zones.sxx[z], m.zones.syy[z], m.zones.sxy[z], m.zones.szz[z]})
      c.number(s, "zone " + std::to_string(z) + " initial stress");
  for (const LoadedEdge& e : m.loadedEdges)
    for (double s : {e.sxx, e.syy, e.sxy}) c.number(s, "boundary stress on an edge");
  for (const DrivenVelocity& d : m.drivenVelocities) c.number(d.value, "boundary velocity");
  for (const TimeFunction& f : m.timeFunctions) {
    for (double v : {f.start, f.rate, f.frequency, f.phase}) c.number(v, "time history parameter");
    for (std::size_t k = 0; k < f.t.size(); ++k) {
      c.number(f.t[k], "time history table time");
      c.number(f.f[k], "time history table value");
    }
  }
  const RunSettings& s = scene.settings;
  for (double v : {s.frac, s.zoneFraction, s.massDamping, s.localDamping, s.stop.time, s.stop.ratio})
    c.number(v, "solver or stop setting");
  for (const HistorySpec& h : scene.histories) c.atLeastOne(h.every, "history '" + h.name + "' every");
  return c.defect();
}

// "" when reading the scene at `path` ends as documented; else what went wrong.
inline std::string readerDefect(const std::string& path) {
  try {
    return modelDefect(readScene(path));
  } catch (const Error&) {
    return "";
  } catch (const std::exception& e) {
    return std::string("internal error (exit code 1): ") + e.what();
  }
}

}  // namespace vdec::fuzz
