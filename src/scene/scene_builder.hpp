#pragma once
// Makes a model, its run settings and its histories from a scene's definitions
// (scene/scene_definition.hpp): resolves names, cuts regions, zones blocks, excavates, selects
// the gridpoints and edges of boundaries and histories, and checks the definitions against each
// other. Every error names the definition's origin (file, line and key when it was read).
#include <cstddef>
#include <string>
#include <vector>

#include "core/model.hpp"
#include "run/cycle.hpp"
#include "run/history.hpp"
#include "scene/scene_definition.hpp"

namespace vdec {

struct Scene {
  std::string title;
  std::string path;
  std::string sha256;                  // of the file's bytes
  std::vector<std::string> overrides;  // --set key=value, applied after reading the file
  // [k]: SHA-256 of the scene as parsed with only its first k [[phase]] tables (a restart's check)
  std::vector<std::string> phasePrefixSha256;
  Model model;
  RunSettings settings;
  std::vector<HistorySpec> histories;
  std::vector<std::string> warnings;   // printed by the command line, kept in results.json
};

// Limits checked before the work they bound (docs/user-manual/scene-format.md#limits): the
// blocks of a scene, with those cut from a region counted by estimateRegion before any cut
// (measured: 100,000 blocks took 15 s and 3.5 GB from reading the scene to results.json), and
// the joint segments a region is cut with.
inline constexpr std::size_t kSceneBlockLimit = 200000;
inline constexpr double kRegionSegmentLimit = 1e7;
// The most zones a scene may have, all deformable blocks together: about 1.5 GB and a few
// seconds of set-up (measured: 1e6 crossed zones set up in 1.1 s, 750 MB in all).
inline constexpr std::size_t kSceneZoneLimit = 2000000;
// Zones per max_edge^2 of area that Delaunay refinement makes (5.04 measured on a square),
// rounded up: the estimate a max_edge zoning is checked by.
inline constexpr double kDelaunayZonesPerArea = 6.0;

// Throws SceneError (a name that resolves to nothing, definitions that contradict each other, a
// limit passed) or GeometryError (bad polygon, sliver zone). The provenance fields (path,
// sha256, overrides, phasePrefixSha256) are the reader's to fill.
Scene buildScene(SceneDefinition definition);

}  // namespace vdec
