#pragma once
// The deformable-block part of a scene: elastic constants of block materials, zoned blocks
// (a quadrilateral with `zoning`, or an `annulus`), [[boundary]] conditions on gridpoints and
// boundary edges, and [initial_stress]. docs/user-manual/scene-format.md documents the keys.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "core/model.hpp"
#include "core/setup_progress.hpp"
#include "geometry/zoning.hpp"
#include "io/table_reader.hpp"

namespace vdec {

// `young` and `poisson`, or `bulk` and `shear`, or none (a material for rigid blocks only).
void readElasticConstants(TableReader& r, BlockMaterial& material);
// Mohr-Coulomb keys of a block material: friction, cohesion, [dilation], [tension]; a warning for
// dilation above friction without cohesion.
void readPlasticity(TableReader& r, BlockMaterial& material, std::vector<std::string>& warnings);

// The most zones a scene may have, all deformable blocks together: about 1.5 GB and a few
// seconds of set-up (measured: 1e6 crossed zones set up in 1.1 s, 750 MB in all).
inline constexpr std::size_t kSceneZoneLimit = 2000000;
// Zones per max_edge^2 of area that Delaunay refinement makes (5.04 measured on a square),
// rounded up: the estimate a max_edge zoning is checked by.
inline constexpr double kDelaunayZonesPerArea = 6.0;

// The zoning of a [[block]]: `annulus = {...}` (then the block has no `vertices`), or
// `zoning = {...}` on a quadrilateral given by `vertices`; nullopt for a rigid block. The zone
// count is checked against what kSceneZoneLimit leaves after `zonesBefore`, before any zone is
// made; a large zoning is announced on `progress`.
std::optional<Mesh> readZoning(TableReader& r, const std::function<Polygon()>& vertices, std::size_t zonesBefore,
                               SetupProgress& progress);

// A block's area, mass and moment of inertia as formed from its shape and its material's
// density: a SceneError naming the block (`where`) and the density's key unless they are finite
// and positive (a density of 1e308 times an area overflows).
void checkMassProperties(const Model& model, const std::string& where, int material, double area, double mass,
                         double inertia);

// Adds a deformable block: its gridpoints and zones, and an entry in Blocks (no contact
// vertices). Throws GeometryError naming the block for degenerate zones.
void addDeformableBlock(Model& model, const std::string& name, int material, const Mesh& mesh);

// Limits of a CSV table file (a `table` history or a `stress_table`), checked before it is read.
inline constexpr std::uintmax_t kTableFileBytes = 64u << 20;
inline constexpr std::size_t kTableRows = 1000000;

// A time history table under `key`, e.g. history = { kind = "sine", frequency = 10.0 }.
TimeFunction readHistory(TableReader& r, const std::string& scenePath, std::string_view key);

// One [[boundary]] table resolved to its block's gridpoints and edges (its history, if any,
// appended to model.timeFunctions); `blockIndex` resolves a block name or fails on `r`.
BoundaryCondition readBoundary(TableReader& r, Model& model, const std::string& path,
                               const std::function<int(TableReader&, std::string_view, const std::string&)>& blockIndex);
// [[boundary]] tables, applied to the model, and [initial_stress].
void readBoundaries(TableReader& top, Model& model, const std::string& path,
                    const std::function<int(TableReader&, std::string_view, const std::string&)>& blockIndex);
void readInitialStress(TableReader& top, Model& model);

// History subjects by position (initial configuration): the block's gridpoint nearest `point`,
// and the zone of the block that holds `point` (-1 when none does).
int nearestGridpoint(const Model& model, int block, Vec2 point);
int zoneAt(const Model& model, int block, Vec2 point);

}  // namespace vdec
