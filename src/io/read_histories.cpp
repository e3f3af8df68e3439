// [[history]] and [[joint_assignment]].
#include <limits>

#include "io/scene_sections.hpp"

namespace vdec {

namespace {

std::array<std::string, 2> twoBlocks(TableReader& r, const std::string& message) {
  const std::vector<std::string> names = r.strings("blocks");
  if (names.size() != 2) r.fail("blocks", message);
  return {names[0], names[1]};
}

HistoryDefinition readHistory(TableReader& r) {
  HistoryDefinition h;
  h.origin = r.origin();
  h.name = r.string("name");
  h.quantity = r.string("quantity");
  const auto info = findHistoryQuantity(h.quantity);
  if (!info) r.fail("quantity", "unknown quantity '" + h.quantity + "'; known: " + historyQuantityNames());
  const HistorySubject subject = info->subject;
  if (subject == HistorySubject::Joint) h.blocks = twoBlocks(r, "a joint history names exactly two blocks");
  else if (subject == HistorySubject::Beam) h.beam = r.string("beam");
  else if (subject == HistorySubject::Cable) h.cable = r.string("cable");
  else if (subject == HistorySubject::Bolt) h.bolt = r.string("bolt");
  else if (subject == HistorySubject::Line) h.from = r.vec2("from"), h.to = r.vec2("to");
  else if (subject != HistorySubject::Model && subject != HistorySubject::Fluid) h.block = r.string("block");
  const bool located = h.quantity.rfind("domain.", 0) == 0 || h.quantity.rfind("knot.", 0) == 0;
  if (subject == HistorySubject::Gridpoint || subject == HistorySubject::Zone || subject == HistorySubject::Beam || subject == HistorySubject::Cable ||
      subject == HistorySubject::Bolt || located)
    h.point = r.vec2("point");
  if (r.has("every")) h.every = static_cast<int>(r.integer("every", 1, std::numeric_limits<int>::max()));
  return h;
}

}  // namespace

void readHistories(TableReader& top, SceneDefinition& scene) {
  for (auto [table, prefix] : top.tables("joint_assignment")) {
    TableReader r(*table, prefix, top.file());
    JointAssignmentDefinition d;
    d.origin = r.origin();
    d.blocks = twoBlocks(r, "must name exactly two blocks");
    d.joint = r.string("joint");
    r.finish();
    scene.jointAssignments.push_back(std::move(d));
  }
  for (auto [table, prefix] : top.tables("history")) {
    TableReader r(*table, prefix, top.file());
    scene.histories.push_back(readHistory(r));
    r.finish();
  }
}

}  // namespace vdec
