#include "core/model.hpp"

#include <algorithm>

namespace vdec {

int Model::jointMaterialFor(int a, int b) const {
  const std::pair<int, int> key{std::min(a, b), std::max(a, b)};
  for (const auto& [pair, joint] : jointAssignments)
    if (pair == key) return joint;
  return defaultJoint;
}

}  // namespace vdec
