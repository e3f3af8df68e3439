// Output files are replaced whole, never written through a link; signals stop a run between steps.
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "run/cycle.hpp"
#include "core/errors.hpp"
#include "core/interrupt.hpp"
#include "io/atomic_file.hpp"
#include "requirements.hpp"
#include "scene_fixture.hpp"

using namespace vdec;
namespace fs = std::filesystem;

namespace {

fs::path freshDirectory(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("vdec-unit-output-" + std::to_string(getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string contents(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

int filesIn(const fs::path& dir) {
  int n = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++n;
  return n;
}

}  // namespace

TEST(AtomicFile, TargetKeepsItsOldContentUntilTheNewFileIsComplete) {
  VDEC_REQUIREMENTS("REQ-IO-010");
  const fs::path dir = freshDirectory("old-until-commit");
  const fs::path target = dir / "results.json";
  std::ofstream(target) << "old results\n";
  {
    AtomicFile file(target.string());
    // More than the stream's buffer, so that part of it has reached the disk.
    file.stream() << std::string(200000, 'x');
    file.stream().flush();
    EXPECT_EQ(contents(target), "old results\n");
    // Given up without commit (an exception on the way): the old file stays, the part goes.
  }
  EXPECT_EQ(contents(target), "old results\n");
  EXPECT_EQ(filesIn(dir), 1);
  {
    AtomicFile file(target.string());
    file.stream() << "new results\n";
    file.commit();
  }
  EXPECT_EQ(contents(target), "new results\n");
  EXPECT_EQ(filesIn(dir), 1);
}

TEST(AtomicFile, SymlinkAtTheTargetIsReplacedNotFollowed) {
  VDEC_REQUIREMENTS("REQ-IO-010");
  const fs::path dir = freshDirectory("symlink");
  const fs::path elsewhere = dir / "elsewhere.txt";
  std::ofstream(elsewhere) << "not vdec's\n";
  const fs::path target = dir / "results.json";
  fs::create_symlink(elsewhere, target);
  writeFileAtomically(target.string(), "new results\n");
  EXPECT_FALSE(fs::is_symlink(target));
  EXPECT_EQ(contents(target), "new results\n");
  EXPECT_EQ(contents(elsewhere), "not vdec's\n");
}

TEST(AtomicFile, UnwritableDirectoryIsAnOutputErrorNamingTheTarget) {
  VDEC_REQUIREMENTS("REQ-IO-010");
  const fs::path dir = freshDirectory("missing");
  const std::string target = (dir / "no-such-directory" / "results.json").string();
  try {
    writeFileAtomically(target, "x");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::Output);
    EXPECT_NE(std::string(e.what()).find(target + ": cannot write"), std::string::npos) << e.what();
  }
}

TEST(Interrupt, RunStopsBeforeTheNextStepAndSaysSo) {
  VDEC_REQUIREMENTS("REQ-IO-011");
  Scene s = vdec::testing::sceneFromText(vdec::testing::blockOnBase(), "interrupt");
  s.settings.stop.cycles = 1000;
  Cycle cycle(s.model, s.settings, s.histories);
  setInterruptSignal(SIGTERM);
  const RunReport report = cycle.run();
  setInterruptSignal(0);
  EXPECT_EQ(report.cycles, 0);
  EXPECT_EQ(report.stopReason, "interrupted");
  EXPECT_EQ(report.interruptSignal, SIGTERM);
  EXPECT_EQ(report.errorCode, static_cast<int>(ExitCode::Interrupted));
  EXPECT_EQ(report.error, "");
}

TEST(InterruptDeathTest, FirstSignalIsRecordedAndASecondOneKills) {
  VDEC_REQUIREMENTS("REQ-IO-011");
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        installInterruptHandlers();
        std::raise(SIGINT);
        if (interruptSignal() != SIGINT) std::_Exit(3);  // the first one only asks
        std::raise(SIGINT);
        std::_Exit(0);
      },
      ::testing::KilledBySignal(SIGINT), "");
}
