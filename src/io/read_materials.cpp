// [model], [[block_material]] and [[joint_material]].
#include <cmath>

#include "io/scene_sections.hpp"

namespace vdec {

namespace {

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

JointMaterialDefinition readJointMaterial(TableReader& r) {
  JointMaterialDefinition d;
  d.origin = r.origin();
  JointMaterial& j = d.material;
  j.name = r.string("name");
  const std::string law = r.string("law", "coulomb-slip");
  if (law == "coulomb-slip") j.law = JointLaw::CoulombSlip;
  else if (law == "coulomb-fracture") j.law = JointLaw::CoulombFracture;
  else if (law == "point-contact") j.law = JointLaw::PointContact;
  else if (law == "continuously-yielding") j.law = JointLaw::ContinuouslyYielding;
  else r.fail("law", "unknown joint law '" + law +
                         "'; use coulomb-slip, coulomb-fracture, continuously-yielding or point-contact");
  j.kn = r.positive("kn");
  j.ks = r.positive("ks");
  readJointFlowKeys(r, j);
  if (j.law == JointLaw::ContinuouslyYielding) {
    readContinuouslyYielding(r, j);
    return d;
  }
  j.tanFriction = std::tan(radians(r.angleDegrees("friction", 0.0)));
  j.tanDilation = std::tan(radians(r.angleDegrees("dilation", 0.0)));
  j.cohesion = r.nonNegative("cohesion", 0.0);
  j.tension = r.nonNegative("tension", 0.0);
  if (j.law == JointLaw::PointContact && (j.cohesion > 0 || j.tension > 0))
    r.fail(j.cohesion > 0 ? "cohesion" : "tension", "the point-contact law has no cohesion or tensile strength");
  return d;
}

}  // namespace

std::optional<MohrCoulombProperties> readMohrCoulomb(TableReader& r, std::vector<std::string>& warnings) {
  if (!r.has("friction") && !r.has("cohesion") && !r.has("dilation") && !r.has("tension")) return std::nullopt;
  const double friction = r.number("friction");
  if (!(friction > 0.0 && friction < 90.0)) r.fail("friction", "must be in (0, 90) degrees, got " + shown(friction));
  const double cohesion = r.number("cohesion");
  if (cohesion < 0.0) r.fail("cohesion", "must be >= 0, got " + shown(cohesion));
  const double dilation = r.number("dilation", 0.0);
  if (!(dilation >= 0.0 && dilation < 90.0)) r.fail("dilation", "must be in [0, 90) degrees, got " + shown(dilation));
  const double phi = radians(friction), psi = radians(dilation);
  MohrCoulombProperties mc;
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
  // 1.4.6.9: a dilation above the friction angle with no cohesion creates energy.
  if (dilation > friction && cohesion == 0.0)
    warnings.push_back(r.location() + ": dilation " + shown(dilation) + " degrees exceeds friction " + shown(friction) +
                       " degrees with zero cohesion: plastic flow then generates energy (1.4.6.9)");
  return mc;
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

void readMaterials(TableReader& top, SceneDefinition& scene) {
  auto t = top.subtable("model");
  if (!t) top.fail("model", "is required: the [model] table sets at least the rounding length");
  ModelDefinition& m = scene.model;
  m.origin = t->origin();
  m.gravity = t->vec2("gravity", {0.0, 0.0});
  m.rounding = t->positive("rounding");
  if (t->has("contact_tolerance")) m.contactTolerance = t->positive("contact_tolerance");
  m.defaultJoint = t->string("default_joint", "");
  t->finish();
  for (auto [table, prefix] : top.tables("block_material")) {
    TableReader r(*table, prefix, top.file());
    BlockMaterialDefinition d;
    d.origin = r.origin();
    BlockMaterial& mat = d.material;
    mat.name = r.string("name");
    mat.density = r.positive("density");
    readElasticConstants(r, mat);
    const bool plastic = r.has("friction") || r.has("cohesion") || r.has("dilation") || r.has("tension");
    if (plastic && !mat.elastic())
      r.fail(r.has("friction") ? "friction" : r.has("cohesion") ? "cohesion" : r.has("dilation") ? "dilation" : "tension",
             "Mohr-Coulomb plasticity needs the elastic constants too (young and poisson, or bulk and shear)");
    if (auto mc = readMohrCoulomb(r, scene.warnings)) {
      mat.plastic = true;
      mat.mohrCoulomb = *mc;
    }
    readThermalKeys(r, mat);
    r.finish();
    scene.blockMaterials.push_back(std::move(d));
  }
  for (auto [table, prefix] : top.tables("joint_material")) {
    TableReader r(*table, prefix, top.file());
    scene.jointMaterials.push_back(readJointMaterial(r));
    r.finish();
  }
}

}  // namespace vdec
