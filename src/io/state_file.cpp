#include "io/state_file.hpp"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>

#include "core/errors.hpp"
#include "core/model_state.hpp"
#include "io/atomic_file.hpp"
#include "io/build_info.hpp"
#include "io/sha256.hpp"

namespace vdec {

namespace {

constexpr char kMagic[8] = {'V', 'D', 'E', 'C', 'S', 'T', 'A', 'T'};

// The sizes of the records saved as bytes: a build whose records differ cannot read the file.
std::string layout() {
  std::ostringstream s;
  s << "Contact " << sizeof(Contact) << " YieldingState " << sizeof(YieldingState) << " VertexGeometry "
    << sizeof(VertexGeometry) << " LoadedEdge " << sizeof(LoadedEdge) << " DrivenVelocity " << sizeof(DrivenVelocity)
    << " ViscousEdge " << sizeof(ViscousEdge) << " RigidViscousEdge " << sizeof(RigidViscousEdge) << " FreeFieldEdge " << sizeof(FreeFieldEdge) << " InitialWave " << sizeof(InitialWave)
    << " MohrCoulombProperties " << sizeof(MohrCoulombProperties) << " EnergyLedger " << sizeof(EnergyLedger)
    << " Monitors " << sizeof(Monitors) << " MotionStepTotals " << sizeof(MotionStepTotals) << " Vec2 " << sizeof(Vec2)
    << " long " << sizeof(long long) << " double " << sizeof(double);
  return s.str();
}

struct Header {
  std::string layoutHash;   // SHA-256 of layout()
  std::string sceneHash;    // the scene with the phases done
  std::string software;     // version and commit that wrote it, for the messages
  std::uint32_t phasesDone = 0;
  std::string phaseName;
};

template <class A>
void visitState(A& a, Header& h) {
  a(h.layoutHash), a(h.sceneHash), a(h.software), a(h.phasesDone), a(h.phaseName);
}

[[noreturn]] void refuse(const std::string& path, const std::string& why) {
  throw RestartError(path + ": " + why);
}

}  // namespace

void writeState(const std::string& path, const Scene& scene, Model& model, Cycle& cycle, int phasesDone) {
  Header header;
  header.layoutHash = sha256Hex(layout());
  // A scene built in code has no file whose phases a restart could check against.
  if (static_cast<std::size_t>(phasesDone) >= scene.phasePrefixSha256.size())
    throw RestartError("a scene built in code (not read from a file) cannot be saved: its phases have no SHA-256 for a "
                       "restart to check");
  header.sceneHash = scene.phasePrefixSha256[phasesDone];
  header.software = std::string(build::version) + " " + build::gitCommit;
  header.phasesDone = static_cast<std::uint32_t>(phasesDone);
  header.phaseName = scene.settings.phases.at(phasesDone - 1).name;
  StateSaver saver;
  saver(header);
  visitState(saver, model);
  cycle.visitState(saver);
  std::string content(kMagic, sizeof kMagic);
  const std::uint32_t version = kStateFormatVersion;
  content.append(reinterpret_cast<const char*>(&version), sizeof version);
  const std::uint64_t size = saver.bytes().size();
  content.append(reinterpret_cast<const char*>(&size), sizeof size);
  content += saver.bytes();
  content += sha256Hex(content);
  writeFileAtomically(path, content);
}

int readState(const std::string& path, const Scene& scene, Model& model, Cycle& cycle) {
  std::ifstream stream(path, std::ios::binary);
  if (!stream) refuse(path, "cannot open the state file");
  std::stringstream buffer;
  buffer << stream.rdbuf();
  const std::string content = buffer.str();
  constexpr std::size_t kFixed = sizeof kMagic + sizeof(std::uint32_t) + sizeof(std::uint64_t);
  if (content.size() < sizeof kMagic || std::memcmp(content.data(), kMagic, sizeof kMagic) != 0)
    refuse(path, "not a vdec state file (it does not start with VDECSTAT); give a file written by vdec run --save");
  if (content.size() < kFixed + 64) refuse(path, "the state file is truncated: save it again");
  std::uint32_t version = 0;
  std::memcpy(&version, content.data() + sizeof kMagic, sizeof version);
  if (version != kStateFormatVersion)
    refuse(path, "state file format " + std::to_string(version) + ", this vdec reads format " +
                     std::to_string(kStateFormatVersion) + ": run the scene's phases again with this vdec and save");
  std::uint64_t size = 0;
  std::memcpy(&size, content.data() + sizeof kMagic + sizeof version, sizeof size);
  if (size != content.size() - kFixed - 64) refuse(path, "the state file is truncated or has bytes added: save it again");
  const std::string body = content.substr(0, content.size() - 64);
  if (sha256Hex(body) != content.substr(content.size() - 64))
    refuse(path, "the state file is damaged (its checksum does not match its contents): save it again");
  try {
    StateLoader loader(std::string_view(body).substr(kFixed));
    Header header;
    loader(header);
    if (header.layoutHash != sha256Hex(layout()))
      refuse(path, "saved by a vdec build whose state layout differs (" + header.software +
                       "): restart with the build that saved it, or run the phases again");
    if (header.phasesDone == 0 || header.phasesDone > scene.settings.phases.size() ||
        header.sceneHash != scene.phasePrefixSha256[header.phasesDone])
      refuse(path, "saved after phase '" + header.phaseName + "' (phase " + std::to_string(header.phasesDone) +
                       ") of a scene that differs from " + scene.path +
                       " in its settings or in its phases up to that one; a restart may only add phases after it");
    visitState(loader, model);
    cycle.visitState(loader);
    if (!loader.finished()) refuse(path, "the state file holds more than a state: save it again");
    return static_cast<int>(header.phasesDone);
  } catch (const StateFormatError& e) {
    refuse(path, std::string("the state file's contents are not a state (") + e.what() + "): save it again");
  }
}

}  // namespace vdec
