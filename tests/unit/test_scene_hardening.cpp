// Hostile scene input: every number of a scene that uses every numeric key is replaced in turn by
// nan, inf, -inf or an integer past its range, and each must give a scene error naming its line,
// never a silent change of the model or a crash. Derived quantities that overflow (a mass, a
// stiffness) are named where they are formed.
#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "run/cycle.hpp"
#include "core/errors.hpp"
#include "io/scene_sections.hpp"
#include "requirements.hpp"
#include "scene_fixture.hpp"

using namespace vdec;

namespace {

const std::filesystem::path kSceneDir = std::filesystem::path(VDEC_TEST_DATA) / "every_number";

std::string fileText(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A number written in the text, outside strings and comments: where it starts, its length and
// its line (from 1).
struct NumberToken {
  std::size_t begin, length;
  int line;
};

std::vector<NumberToken> numberTokens(const std::string& text) {
  std::vector<NumberToken> tokens;
  int line = 1;
  bool inString = false, inComment = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      inComment = false;
      continue;
    }
    if (inComment) continue;
    if (c == '"') inString = !inString;
    if (inString) continue;
    if (c == '#') {
      inComment = true;
      continue;
    }
    const bool signedDigit = (c == '-' || c == '+') && i + 1 < text.size() && std::isdigit(text[i + 1]);
    const bool startsWord = i > 0 && (std::isalnum(text[i - 1]) || text[i - 1] == '_' || text[i - 1] == '.');
    if ((std::isdigit(c) || signedDigit) && !startsWord) {
      std::size_t j = i + 1;
      while (j < text.size() && (std::isdigit(text[j]) || text[j] == '.' || text[j] == 'e' ||
                                 ((text[j] == '-' || text[j] == '+') && text[j - 1] == 'e')))
        ++j;
      tokens.push_back({i, j - i, line});
      i = j - 1;
    }
  }
  return tokens;
}

bool isInteger(const std::string& token) { return token.find_first_of(".e") == std::string::npos; }

// Writes `text` as scene.toml (and the tables as given) in a fresh folder; returns its path.
std::string writeScene(const std::string& name, const std::string& text, const std::string& ramp,
                       const std::string& far) {
  const auto dir = vdec::testing::unitTestFolder() / name;
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "scene.toml") << text;
  std::ofstream(dir / "ramp.csv") << ramp;
  std::ofstream(dir / "far.csv") << far;
  return (dir / "scene.toml").string();
}

// The SceneError the scene raises, or "" when it reads; any other error is a test failure.
std::string readError(const std::string& path, const std::vector<std::string>& overrides = {}) {
  try {
    readScene(path, overrides);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

// As readError, through the set-up of the run too (zone masses and the time step are formed there).
std::string setupError(const std::string& path, const std::vector<std::string>& overrides) {
  try {
    Scene s = readScene(path, overrides);
    Cycle cycle(s.model, s.settings, s.histories);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

struct Files {
  std::string scene = fileText(kSceneDir / "scene.toml");
  std::string ramp = fileText(kSceneDir / "ramp.csv");
  std::string far = fileText(kSceneDir / "far.csv");
};

}  // namespace

TEST(SceneHardening, TheSceneOfEveryNumericKeyReadsAndRuns) {
  VDEC_REQUIREMENTS("REQ-IO-004");
  const Files f;
  const std::string path = writeScene("every-number", f.scene, f.ramp, f.far);
  Scene s = readScene(path);
  EXPECT_GT(s.model.zones.size(), 0);
  EXPECT_GT(s.model.blocks.size(), 5);
  Cycle cycle(s.model, s.settings, s.histories);
  const RunReport report = cycle.run();
  EXPECT_EQ(report.errorCode, 0) << report.error;
  EXPECT_GT(numberTokens(f.scene).size(), 100u);
}

TEST(SceneHardening, NanAndInfinityAnywhereInTheSceneAreErrorsNamingTheLine) {
  VDEC_REQUIREMENTS("REQ-IO-004");
  const Files f;
  int checked = 0;
  for (const NumberToken& t : numberTokens(f.scene)) {
    const std::string original = f.scene.substr(t.begin, t.length);
    for (const char* bad : {"nan", "inf", "-inf"}) {
      std::string text = f.scene;
      text.replace(t.begin, t.length, bad);
      const std::string e = readError(writeScene("nan-number", text, f.ramp, f.far));
      const std::string at = "scene.toml:" + std::to_string(t.line) + ": key '";
      EXPECT_NE(e.find(at), std::string::npos) << "line " << t.line << " '" << original << "' -> " << bad << ": " << e;
      const bool named = e.find(isInteger(original) ? "must be an integer" : "must be finite, got ") != std::string::npos;
      EXPECT_TRUE(named) << "line " << t.line << " '" << original << "' -> " << bad << ": " << e;
      ++checked;
    }
  }
  EXPECT_GT(checked, 300);
}

TEST(SceneHardening, NanAndInfinityInTableFilesAreErrorsNamingFileAndLine) {
  VDEC_REQUIREMENTS("REQ-IO-004");
  const Files f;
  for (const bool stressTable : {false, true}) {
    const std::string& table = stressTable ? f.far : f.ramp;
    const std::string file = stressTable ? "far.csv" : "ramp.csv";
    const std::string key = stressTable ? "boundary[2].stress_table" : "block[1].velocity_history.file";
    for (const NumberToken& t : numberTokens(table)) {
      for (const char* bad : {"nan", "inf", "-inf", "1e999"}) {
        std::string text = table;
        text.replace(t.begin, t.length, bad);
        const std::string e = stressTable ? readError(writeScene("nan-table", f.scene, f.ramp, text))
                                          : readError(writeScene("nan-table", f.scene, text, f.far));
        EXPECT_NE(e.find("key '" + key + "'"), std::string::npos) << e;
        EXPECT_NE(e.find(file + ":" + std::to_string(t.line) + ": '" + bad + "' is not a finite number"),
                  std::string::npos) << e;
      }
    }
  }
}

TEST(SceneHardening, IntegersPastTheirRangeAreErrorsOrHeldExactlyNeverWrapped) {
  VDEC_REQUIREMENTS("REQ-IO-004");
  const Files f;
  for (const NumberToken& t : numberTokens(f.scene)) {
    const std::string original = f.scene.substr(t.begin, t.length);
    if (!isInteger(original)) continue;
    for (const char* big : {"4294967296", "9223372036854775807", "-4294967296", "0"}) {
      std::string text = f.scene;
      text.replace(t.begin, t.length, big);
      const std::string path = writeScene("big-integer", text, f.ramp, f.far);
      const std::string e = readError(path, {"stop.cycles=3"});
      if (!e.empty()) {
        EXPECT_NE(e.find("scene.toml:" + std::to_string(t.line) + ": key '"), std::string::npos) << e;
        continue;
      }
      // Read: then it must also run (a divisor that wrapped to 0 once killed the process).
      Scene s = readScene(path, {"stop.cycles=3"});
      Cycle cycle(s.model, s.settings, s.histories);
      EXPECT_EQ(cycle.run().errorCode, 0) << "line " << t.line << ": " << big;
    }
  }
}

TEST(SceneHardening, HistoryEveryBeyondAnIntIsAnErrorNamingTheKey) {
  VDEC_REQUIREMENTS("REQ-IO-004");
  const Files f;
  const std::string path = writeScene("every-2-32", f.scene, f.ramp, f.far);
  const std::string e = readError(path, {"history[0].every=4294967296"});
  EXPECT_NE(e.find("key 'history[0].every': must be an integer in [1, 2147483647], got 4294967296"), std::string::npos)
      << e;
}

TEST(SceneHardening, OverflowingMassAndStiffnessAreNamedWhereTheyAreFormed) {
  VDEC_REQUIREMENTS("REQ-IO-004");
  const Files f;
  const std::string path = writeScene("overflow", f.scene, f.ramp, f.far);
  // block_material[0] "rock": rigid blocks, the ring and the triangle; [1] "soft": the slab.
  const std::string rigid = readError(path, {"block_material[0].density=1e308"});
  EXPECT_NE(rigid.find("block 'base' (block[0], line"), std::string::npos) << rigid;
  EXPECT_NE(rigid.find("is inf kg/m, not a finite positive number: lower block_material[0].density"), std::string::npos)
      << rigid;
  const std::string deformable = readError(path, {"block_material[1].density=1e308"});
  EXPECT_NE(deformable.find("block 'slab': its mass, block_material[1].density (1e+308 kg/m^3)"), std::string::npos)
      << deformable;
  const std::string modulus = setupError(path, {"block_material[1].bulk=1.7e308", "block_material[1].shear=1.7e308"});
  EXPECT_NE(modulus.find("of block 'slab': its mass"), std::string::npos) << modulus;
  EXPECT_NE(modulus.find("lower block_material[1].density, its elastic moduli"), std::string::npos) << modulus;
  const std::string young = readError(path, {"block_material[0].young=1e308", "block_material[0].poisson=0.49"});
  EXPECT_NE(young.find("key 'block_material[0].young': with poisson 0.49 gives a bulk modulus of inf"),
            std::string::npos) << young;
  const std::string weight = readError(path, {"model.gravity=[0.0, -1e305]"});
  EXPECT_NE(weight.find("key 'model.gravity': its magnitude times the mass of block 'base' (30000 kg/m)"),
            std::string::npos) << weight;
  const std::string joint = setupError(path, {"joint_material[0].kn=1e308"});
  EXPECT_NE(joint.find("the rigid-block time step (1.3-28)"), std::string::npos) << joint;
  EXPECT_NE(joint.find("lower [[joint_material]] kn and ks"), std::string::npos) << joint;
}

TEST(SceneHardening, CoordinatesWhoseSquaresOverflowAreAGeometryErrorNamingTheBlock) {
  VDEC_REQUIREMENTS("REQ-IO-004");
  const Files f;
  const std::string path = writeScene("huge-coordinates", f.scene, f.ramp, f.far);
  try {
    readScene(path, {"block[1].vertices=[[5.0, 0.0], [6e200, 0.0], [6e200, 1.0], [5.0, 1.0]]"});
    FAIL() << "no error";
  } catch (const GeometryError& e) {
    EXPECT_NE(std::string(e.what()).find("block 'driven' (block[1], line"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("overflows"), std::string::npos) << e.what();
  }
}

TEST(SceneHardening, TableFilesThatAreDevicesOrTooLargeAreRefusedBeforeTheyAreRead) {
  VDEC_REQUIREMENTS("REQ-IO-005");
  const Files f;
  const std::string path = writeScene("table-limits", f.scene, f.ramp, f.far);
  const std::string key = "key 'block[1].velocity_history.file': ";
  for (const char* device : {"/dev/zero", "/dev/urandom"}) {
    const std::string e = readError(path, {std::string("block[1].velocity_history.file=\"") + device + "\""});
    EXPECT_NE(e.find(key + "'" + device + "' is not a regular file"), std::string::npos) << e;
  }
  const auto dir = std::filesystem::path(path).parent_path();
  std::ofstream(dir / "huge.csv") << "t, f\n";
  std::filesystem::resize_file(dir / "huge.csv", kTableFileBytes + 1);  // sparse: nothing is written
  const std::string huge = readError(path, {"block[1].velocity_history.file=\"huge.csv\""});
  EXPECT_NE(huge.find(key + "'" + (dir / "huge.csv").string() + "' has 67108865 bytes, more than the limit of 67108864"),
            std::string::npos) << huge;
  {
    std::ofstream rows(dir / "rows.csv");
    for (std::size_t i = 0; i <= kTableRows; ++i) rows << i << ",0\n";
  }
  const std::string many = readError(path, {"block[1].velocity_history.file=\"rows.csv\""});
  EXPECT_NE(many.find((dir / "rows.csv").string() + ":1000001: more than 1000000 rows"), std::string::npos) << many;
  std::filesystem::remove(dir / "huge.csv");
  std::filesystem::remove(dir / "rows.csv");
}

TEST(HistoryBound, AFullSeriesKeepsTheSamplesOfTheDoubledIntervalAndDoublesIt) {
  VDEC_REQUIREMENTS("REQ-IO-006");
  for (const bool atZero : {true, false}) {
    // Sampled every 3 cycles with a limit of 8: sample k at cycle (k + first) * 3.
    HistorySeries series;
    series.every = 3;
    series.sampledAtCycleZero = atZero;
    const long long first = atZero ? 0 : 3;
    std::vector<long long> halvedAt;
    for (long long cycle = first; cycle <= 600; ++cycle) {
      if (cycle % series.every != 0) continue;
      if (appendHistorySample(series, 0.5 * static_cast<double>(cycle), static_cast<double>(cycle), 8))
        halvedAt.push_back(cycle);
      EXPECT_LT(series.t.size(), 8u);
    }
    EXPECT_EQ(series.halvings, static_cast<int>(halvedAt.size()));
    EXPECT_EQ(series.every, 3LL << series.halvings);
    ASSERT_GE(series.halvings, 3);
    // What is kept is what sampling every `series.every` from the start records.
    std::vector<double> expected;
    for (long long cycle = atZero ? 0 : series.every; cycle <= 600; cycle += series.every)
      expected.push_back(static_cast<double>(cycle));
    EXPECT_EQ(series.value, expected) << (atZero ? "sampled at cycle 0" : "first sample at cycle every");
    for (std::size_t k = 0; k < series.t.size(); ++k) EXPECT_EQ(series.t[k], 0.5 * series.value[k]);
  }
}
