// Contacts over a run: one contact per place where two blocks touch, kept through corners
// sliding past each other, with the face load carried without a gap in support.
#include <cmath>
#include <map>

#include "contact/contact_detection.hpp"
#include "contact/contact_geometry.hpp"
#include "run/cycle.hpp"
#include "requirements.hpp"
#include "scene_fixture.hpp"

using namespace vdec;
using vdec::testing::sceneFromText;

namespace {

std::string materials(double friction) {
  return R"(
[[block_material]]
name = "rock"
density = 2500.0
[[joint_material]]
name = "j"
kn = 1e9
ks = 1e9
friction = )" + std::to_string(friction) + "\n";
}

std::string square(const std::string& name, double x, double y, const std::string& extra = "") {
  auto p = [](double a, double b) { return "[" + std::to_string(a) + ", " + std::to_string(b) + "]"; };
  return "[[block]]\nname = \"" + name + "\"\nmaterial = \"rock\"\nvertices = [" + p(x, y) + ", " + p(x + 1, y) +
         ", " + p(x + 1, y + 1) + ", " + p(x, y + 1) + "]\n" + extra;
}

}  // namespace

TEST(ContactLifecycle, AlignedFacesOfALatticeHaveOneContactAtEachEnd) {
  VDEC_REQUIREMENTS("REQ-CONTACT-002");
  // A 2 x 2 lattice on a base: four blocks meet at (1, 1), where each corner touches three
  // others. Every shared face must carry exactly two closed contacts whose lengths sum to the
  // face length; a third or fourth would double the face's stiffness.
  std::string text = "[model]\nrounding = 0.01\n[stop]\ncycles = 1\n" + materials(30.0);
  text += "[[block]]\nname = \"base\"\nmaterial = \"rock\"\nvertices = [[0.0, -1.0], [2.0, -1.0], [2.0, 0.0], "
          "[0.0, 0.0]]\nfix = [\"x\", \"y\", \"rotation\"]\n";
  text += square("a", 0, 0) + square("b", 1, 0) + square("c", 0, 1) + square("d", 1, 1);
  Scene s = sceneFromText(text, "lattice");
  ContactDetection detection;
  detection.initialise(s.model);
  std::map<std::pair<int, int>, std::pair<int, double>> faces;  // closed contacts and total length
  for (const Contact& c : s.model.contacts) {
    if (c.open) continue;
    auto& face = faces[{std::min(c.blockA, c.blockB), std::max(c.blockA, c.blockB)}];
    ++face.first;
    face.second += c.length;
  }
  // base-a, base-b (1 m each of the base's top), a-b, a-c, b-d, c-d.
  ASSERT_EQ(faces.size(), 6u);
  for (const auto& [pair, face] : faces) {
    EXPECT_EQ(face.first, 2) << s.model.blocks.name[pair.first] << "-" << s.model.blocks.name[pair.second];
    EXPECT_NEAR(face.second, 1.0, 1e-12) << s.model.blocks.name[pair.first] << "-" << s.model.blocks.name[pair.second];
  }
}

TEST(ContactLifecycle, CornersSlidingPastEachOtherKeepTheFaceSupported) {
  VDEC_REQUIREMENTS("REQ-CONTACT-004");
  // An upper block starts exactly on a fixed lower one (corners on corners) and is driven
  // sideways on a frictionless joint by three rounding lengths. At each end of the face the
  // corner-corner contact must hand over to the corner that moves onto the other block's face:
  // if it did not, one end would lose its support until the next detection scan and the block
  // would tip. Settled by mass damping, the joint must carry the weight all the way.
  std::string text = "[model]\nrounding = 0.01\ngravity = [0.0, -10.0]\n[stop]\ntime = 0.3\n"
                     "[solver]\nmass_damping = 300.0\n" + materials(0.0);
  text += square("lower", 0, 0, "fix = [\"x\", \"y\", \"rotation\"]\n");
  text += square("upper", 0, 1, "fix = [\"x\"]\nvelocity = [0.1, 0.0]\n");
  text += "[[history]]\nname = \"fn\"\nquantity = \"joint.normal_force\"\nblocks = [\"upper\", \"lower\"]\n";
  text += "[[history]]\nname = \"theta\"\nquantity = \"block.rotation\"\nblock = \"upper\"\n";
  text += "[[history]]\nname = \"n\"\nquantity = \"joint.contacts\"\nblocks = [\"upper\", \"lower\"]\n";
  Scene s = sceneFromText(text, "slide");
  Cycle cycle(s.model, s.settings, s.histories);
  const RunReport report = cycle.run();
  ASSERT_EQ(report.errorCode, 0) << report.error;
  const double weight = 2500.0 * 10.0;
  const HistorySeries& fn = report.histories[0];
  const HistorySeries& theta = report.histories[1];
  const HistorySeries& count = report.histories[2];
  int checked = 0;
  for (std::size_t i = 0; i < fn.t.size(); ++i) {
    if (fn.t[i] < 0.1) continue;  // settling: about ten damping times
    EXPECT_NEAR(fn.value[i], weight, 1e-3 * weight) << "t = " << fn.t[i];
    EXPECT_LE(count.value[i], 2.0) << "t = " << fn.t[i];
    ++checked;
  }
  EXPECT_GT(checked, 100);
  for (double th : theta.value) EXPECT_LT(std::abs(th), 1e-5);
  EXPECT_NEAR(s.model.blocks.centroid[1].x - 0.5, 0.03, 1e-3);
}

TEST(ContactLifecycle, AnOpenContactIsEvaluatedAgainBeforeItCanClose) {
  VDEC_REQUIREMENTS("REQ-CONTACT-004");
  // A block dropped from a gap of half the contact tolerance, tilted so that one corner lands
  // first: its contacts start open and are skipped while the motion so far cannot have closed
  // them. Whenever a contact's corner actually touches, the contact must have been evaluated in
  // that step, i.e. carry the overlap the geometry has now.
  std::string text = "[model]\nrounding = 0.01\ngravity = [0.0, -10.0]\n[stop]\ncycles = 1\n" + materials(30.0);
  text += "[[block]]\nname = \"base\"\nmaterial = \"rock\"\nvertices = [[-2.0, -1.0], [3.0, -1.0], [3.0, 0.0], "
          "[-2.0, 0.0]]\nfix = [\"x\", \"y\", \"rotation\"]\n";
  text += "[[block]]\nname = \"top\"\nmaterial = \"rock\"\nvertices = [[0.0, 0.005], [1.0, 0.006], [1.0, 1.006], "
          "[0.0, 1.005]]\n";
  Scene s = sceneFromText(text, "drop");
  s.settings.stop.cycles = 3000;
  s.settings.snapshotEvery = 1;
  int closedSeen = 0, failures = 0;
  s.settings.snapshot = [&](const Model& m) {
    for (const Contact& c : m.contacts) {
      // The contact stage saw the positions before this step's motion: a contact evaluated in
      // this step differs from the geometry now by at most the motion of one step (twice the
      // largest vertex displacement); a skipped one would be stale by many.
      const FeatureHit now = followFeature(m, c.corner, c.blockB, c.feature, c.featureKind);
      if (now.overlap <= 0.0 || m.cycle == 0) continue;
      ++closedSeen;
      const double dt = m.time / static_cast<double>(m.cycle);
      const double step = 2.0 * (norm(m.blocks.velocity[1]) + std::abs(m.blocks.angularVelocity[1]) * m.blocks.boundingRadius[1]) * dt;
      if (std::abs(c.overlap - now.overlap) > step * (1.0 + 1e-9)) ++failures;
    }
  };
  Cycle cycle(s.model, s.settings, s.histories);
  cycle.run();
  EXPECT_GT(closedSeen, 1000);
  EXPECT_EQ(failures, 0);
}

TEST(ContactLifecycle, PartialRescansKeepAContactAtEveryTouchingCorner) {
  VDEC_REQUIREMENTS("REQ-CONTACT-004");
  // A block driven across a row of fixed blocks, riding their faces and corners: only it moves,
  // so only it (and the pairs it takes part in) is rescanned. Every corner that touches another
  // block must have its own contact, except for the step or two after two corners pass each
  // other: the corner-corner contact between them follows one corner onto the other's face, and
  // the other corner's own contact on the face it now rests on comes from the scan that the
  // passing asks for at the next step (without it, not until the motion calls for a scan).
  std::string text = "[model]\nrounding = 0.01\ngravity = [0.0, -10.0]\n[solver]\nmass_damping = 200.0\n[stop]\ncycles = 1\n" +
                     materials(30.0);
  text += "[[block]]\nname = \"base\"\nmaterial = \"rock\"\nvertices = [[-1.0, -1.0], [7.0, -1.0], [7.0, 0.0], "
          "[-1.0, 0.0]]\nfix = [\"x\", \"y\", \"rotation\"]\n";
  for (int i = 0; i < 6; ++i)
    text += square("r" + std::to_string(i), i, 0, "fix = [\"x\", \"y\", \"rotation\"]\n");
  text += "[[block]]\nname = \"rider\"\nmaterial = \"rock\"\nvertices = [[0.25, 1.0], [0.75, 1.0], [0.75, 1.5], "
          "[0.25, 1.5]]\nfix = [\"x\", \"rotation\"]\nvelocity = [2.0, 0.0]\n";
  Scene s = sceneFromText(text, "rider");
  s.settings.stop.cycles = 10000;
  s.settings.snapshotEvery = 1;
  int touching = 0, longestWithout = 0;
  std::map<std::pair<int, int>, int> without;  // (corner, block) -> steps touching with no contact of its own
  s.settings.snapshot = [&](const Model& m) {
    for (int a = 0; a < m.blocks.size(); ++a)
      for (int b = 0; b < m.blocks.size(); ++b) {
        if (a == b || (m.blocks.driven[a] == DriveAll && m.blocks.driven[b] == DriveAll)) continue;
        const int first = m.blocks.firstVertex[a];
        for (int v = first; v < first + m.blocks.vertexCount[a]; ++v) {
          int& steps = without[{v, b}];
          const FeatureHit hit = nearestFeature(m, v, b);
          bool own = false;
          for (const Contact& c : m.contacts) own = own || (c.corner == v && c.blockB == b);
          // Two touching corners have one contact between them: either corner's will do.
          if (hit.kind == FeatureKind::Corner)
            for (const Contact& c : m.contacts) own = own || (c.corner == hit.feature && c.blockB == a);
          if (hit.overlap <= 0.0 || own) {
            steps = 0;
            continue;
          }
          ++touching;
          longestWithout = std::max(longestWithout, ++steps);
        }
      }
  };
  Cycle cycle(s.model, s.settings, s.histories);
  const RunReport report = cycle.run();
  EXPECT_GT(report.detectionScans, 100);  // the rider crosses 4 m: many rescans of its own
  EXPECT_LE(longestWithout, 2);
  EXPECT_GT(s.model.blocks.centroid[7].x, 4.5);
}

TEST(ContactLifecycle, ABlockLeftOutOfARescanCannotCloseOnItsNeighbourUnseen) {
  VDEC_REQUIREMENTS("REQ-CONTACT-004");
  // Tolerance 0.01 m, gap 8 mm. A backs off 2.4 mm; B slides 5.1 mm sideways, which calls a
  // rescan that, across a gap now wider than the tolerance, drops their contacts. Then A comes
  // back 7.3 mm (4.9 mm past its first place) and B approaches 4.9 mm: 12.2 mm against a gap
  // of 10.4. With a rescan due only past half the tolerance and only blocks past a quarter of
  // it going along, A is left out of B's rescan and neither reaches the limit again: the faces
  // meet with no contact. The rule 2 T + C <= tol must call a scan first.
  std::string text = "[model]\nrounding = 0.01\n[stop]\ncycles = 1\n" + materials(30.0);
  text += "[[block]]\nname = \"A\"\nmaterial = \"rock\"\nvertices = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]\n";
  text += "[[block]]\nname = \"B\"\nmaterial = \"rock\"\nvertices = [[1.008, 0.0], [2.008, 0.0], [2.008, 1.0], "
          "[1.008, 1.0]]\n";
  Scene s = sceneFromText(text, "left-out");
  Model& m = s.model;
  ContactDetection detection;
  detection.initialise(m);
  ASSERT_EQ(m.contacts.size(), 2u);
  m.cycle = 1;
  int touchingWithout = 0, touching = 0;
  auto move = [&](int b, Vec2 total, int steps) {
    for (int i = 0; i < steps; ++i) {
      m.blocks.centroid[b] += (1.0 / steps) * total;
      placeBlockVertices(m, b);
      detection.update(m, norm(total) / steps);
      ++m.cycle;
      for (int a = 0; a < 2; ++a)
        for (int v = m.blocks.firstVertex[a]; v < m.blocks.firstVertex[a] + 4; ++v) {
          if (nearestFeature(m, v, 1 - a).overlap <= 0.0) continue;
          ++touching;
          if (m.contacts.empty()) ++touchingWithout;
        }
    }
  };
  move(0, {-0.0024, 0.0}, 24);
  move(1, {0.0, 0.0051}, 51);
  ASSERT_TRUE(m.contacts.empty());  // the rescan dropped them, across 10.4 mm
  move(0, {0.0073, 0.0}, 73);
  move(1, {-0.0049, 0.0}, 49);
  EXPECT_GT(touching, 0);           // the faces do meet
  EXPECT_EQ(touchingWithout, 0);
}

TEST(ContactLifecycle, SideArraysFollowTheirContactsThroughPartialAndFullScans) {
  VDEC_REQUIREMENTS("REQ-CONTACT-004");
  // The continuously-yielding state lives in an array beside the contacts; every scan reorders,
  // drops and adds contacts, and the state must stay with its contact. A rider slides across a
  // row of fixed blocks on continuously-yielding joints, rescanned alone (partial scans) and at
  // times with every block (full scans): each contact's state is tagged with its key when it
  // first appears, and after every step every contact must still carry its own tag.
  std::string text = "[model]\nrounding = 0.01\ngravity = [0.0, -10.0]\n[solver]\nmass_damping = 200.0\n[stop]\ncycles = 1\n"
                     "[[block_material]]\nname = \"rock\"\ndensity = 2500.0\n[[joint_material]]\nname = \"j\"\n"
                     "law = \"continuously-yielding\"\nkn = 1e9\nks = 1e9\nfriction = 30.0\nroughness = 5e-4\n";
  text += "[[block]]\nname = \"base\"\nmaterial = \"rock\"\nvertices = [[-1.0, -1.0], [7.0, -1.0], [7.0, 0.0], "
          "[-1.0, 0.0]]\nfix = [\"x\", \"y\", \"rotation\"]\n";
  for (int i = 0; i < 6; ++i) text += square("r" + std::to_string(i), i, 0, "fix = [\"x\", \"y\", \"rotation\"]\n");
  text += "[[block]]\nname = \"rider\"\nmaterial = \"rock\"\nvertices = [[0.25, 1.0], [0.75, 1.0], [0.75, 1.5], "
          "[0.25, 1.5]]\nfix = [\"x\", \"rotation\"]\nvelocity = [2.0, 0.0]\n";
  Scene s = sceneFromText(text, "cy-rider");
  ContactDetection detection;
  detection.initialise(s.model);
  Model& m = s.model;
  auto tag = [](const Contact& c) { return 1.0 + c.corner * 1000.0 + c.blockB; };
  int checked = 0, fresh = 0;
  for (int step = 0; step < 400; ++step) {
    ASSERT_EQ(m.yieldingStates.size(), m.contacts.size());
    for (std::size_t i = 0; i < m.contacts.size(); ++i) {
      YieldingState& y = m.yieldingStates[i];
      if (y.plasticShear == 0.0) {  // a contact the scan made: tag it
        y.plasticShear = tag(m.contacts[i]);
        ++fresh;
      }
      ASSERT_EQ(y.plasticShear, tag(m.contacts[i])) << "step " << step << ", contact " << i;
      ++checked;
    }
    // Move the rider by 2 cm and rescan it alone; every tenth step, every block.
    const int rider = m.blocks.size() - 1;
    m.blocks.centroid[rider].x += 0.02;
    placeBlockVertices(m, rider);
    if (step % 10 == 9) {
      std::vector<int> all(m.blocks.size());
      for (int b = 0; b < m.blocks.size(); ++b) all[b] = b;
      detection.requestRescan(all);
    } else {
      detection.requestRescan({rider});
    }
    m.cycle = step + 1;
    detection.update(m, 0.02);
  }
  EXPECT_GT(fresh, 20);     // contacts came and went along the row
  EXPECT_GT(checked, 1000);
}
