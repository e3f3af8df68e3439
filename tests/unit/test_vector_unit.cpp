// The zone and gridpoint loops' versions for each vector unit give bitwise the same results.

#include <string>
#include <tuple>

#include "core/vector_unit.hpp"
#include "requirements.hpp"
#include "run/cycle.hpp"
#include "scene_fixture.hpp"

using namespace vdec;
using vdec::testing::sceneFromText;

namespace {

// Two distorted quadrilaterals 10 m apart, 24 x 20 crossed cells each (1 920 zones): one of
// elastic rock, whose tiles take the vectorised path throughout, and one of Mohr-Coulomb rock,
// whose tiles go zone by zone. Each is fixed at its base and pressed and sheared on top, hard
// enough to yield the weak one in part, under gravity and the given damping.
std::string twoBlocks(const std::string& damping) {
  std::string text = R"(
[model]
gravity = [0.0, -10.0]
rounding = 0.01
[solver]
)" + damping + R"(
[stop]
cycles = 400
[[block_material]]
name = "rock"
density = 2500.0
young = 10e9
poisson = 0.25
[[block_material]]
name = "weak"
density = 2500.0
young = 10e9
poisson = 0.25
friction = 35.0
cohesion = 2e6
[[joint_material]]
name = "joint"
kn = 1e10
ks = 1e10
)";
  for (const auto& [name, material, shift] : {std::tuple{"solid", "rock", 0.0}, std::tuple{"patch", "weak", 10.0}}) {
    auto x = [shift = shift](double v) { return std::to_string(v + shift); };
    text += std::string("[[block]]\nname = \"") + name + "\"\nmaterial = \"" + material + "\"\nvertices = [[" + x(0.0) +
            ", 0.0], [" + x(2.0) + ", 0.3], [" + x(2.4) + ", 1.9], [" + x(-0.2) + ", 1.5]]\n" +
            "zoning = { nx = 24, ny = 20 }\n[[boundary]]\nblock = \"" + name + "\"\nx = [" + x(-0.01) + ", " + x(2.01) +
            "]\ny = [-0.01, 0.31]\nfix = [\"x\", \"y\"]\n[[boundary]]\nblock = \"" + name + "\"\nx = [" + x(-0.21) +
            ", " + x(2.41) + "]\ny = [1.49, 1.91]\nstress = [0.0, -6e6, 2e6]\n";
  }
  return text;
}

struct Outcome {
  Model model;
  RunReport report;
};

Outcome runOn(VectorUnit unit, const std::string& damping) {
  EXPECT_TRUE(setVectorUnit(unit));
  Scene s = sceneFromText(twoBlocks(damping), "vector-unit");
  Cycle cycle(s.model, s.settings, {});
  RunReport r = cycle.run();
  EXPECT_EQ(r.errorCode, 0) << r.error;
  return {s.model, r};
}

void expectBitwiseEqual(const Outcome& a, const Outcome& b) {
  ASSERT_EQ(a.model.gridpoints.size(), b.model.gridpoints.size());
  int differing = 0;
  for (int i = 0; i < a.model.gridpoints.size(); ++i) {
    const Vec2 pa = a.model.gridpoints.position[i], pb = b.model.gridpoints.position[i];
    const Vec2 va = a.model.gridpoints.velocity[i], vb = b.model.gridpoints.velocity[i];
    differing += pa.x != pb.x || pa.y != pb.y || va.x != vb.x || va.y != vb.y;
  }
  for (int z = 0; z < a.model.zones.size(); ++z)
    differing += a.model.zones.sxx[z] != b.model.zones.sxx[z] || a.model.zones.syy[z] != b.model.zones.syy[z] ||
                 a.model.zones.sxy[z] != b.model.zones.sxy[z] || a.model.zones.szz[z] != b.model.zones.szz[z] ||
                 a.model.zones.plasticState[z] != b.model.zones.plasticState[z];
  EXPECT_EQ(differing, 0);
  EXPECT_EQ(a.report.energy.kinetic, b.report.energy.kinetic);
  EXPECT_EQ(a.report.energy.strain, b.report.energy.strain);
  EXPECT_EQ(a.report.energy.plasticDissipation, b.report.energy.plasticDissipation);
  EXPECT_EQ(a.report.energy.dampingDissipation, b.report.energy.dampingDissipation);
}

}  // namespace

TEST(VectorUnit, EveryUnitGivesBitwiseTheSameResults) {
  VDEC_REQUIREMENTS("REQ-ZONE-021");
  struct Restore {
    VectorUnit unit = vectorUnit();
    ~Restore() { setVectorUnit(unit); }
  } restore;
  for (const std::string damping : {"mass_damping = 200.0", "stiffness_damping = 2e-5", "local_damping = 0.8"}) {
    SCOPED_TRACE(damping);
    const Outcome baseline = runOn(VectorUnit::Baseline, damping);
    // The scene does what it is meant to: zones of the weak block yield, not all of them.
    int yielding = 0;
    for (int z = 0; z < baseline.model.zones.size(); ++z) yielding += baseline.model.zones.plasticState[z] != 0;
    EXPECT_EQ(baseline.model.zones.size(), 2 * 1920);
    EXPECT_GT(yielding, 0);
    EXPECT_LT(yielding, 1920);
    for (const VectorUnit unit : {VectorUnit::Avx2, VectorUnit::Avx512}) {
      if (!vectorUnitSupported(unit)) continue;
      SCOPED_TRACE(vectorUnitName(unit));
      expectBitwiseEqual(baseline, runOn(unit, damping));
    }
  }
}

TEST(VectorUnit, TheWidestSupportedUnitIsChosenAndAnUnsupportedOneRefused) {
  VDEC_REQUIREMENTS("REQ-ZONE-021");
  EXPECT_TRUE(vectorUnitSupported(VectorUnit::Baseline));
  const VectorUnit widest = vectorUnit();
  EXPECT_EQ(widest, widestVectorUnit());
  for (const VectorUnit unit : {VectorUnit::Avx512, VectorUnit::Avx2, VectorUnit::Baseline})
    if (vectorUnitSupported(unit)) {
      EXPECT_EQ(widest, unit);
      break;
    }
  for (const VectorUnit unit : {VectorUnit::Avx512, VectorUnit::Avx2})
    if (!vectorUnitSupported(unit)) {
      EXPECT_FALSE(setVectorUnit(unit));
      EXPECT_EQ(vectorUnit(), widest);
    }
}
