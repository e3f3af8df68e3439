#pragma once
// The elastic square block of the zone benchmarks (elastic_zone_bench.cpp, zone_cycles.cpp):
// 10 m x 10 m, E = 10 GPa, nu = 0.25, density 2500 kg/m^3, no gravity, n x n crossed cells, the
// bottom edge fixed in x and y, syy = -1 MPa on the top edge, mass damping 400 1/s. Defined in
// code and made by vdec::buildScene, the builder the scene reader uses.
#include <string>

#include "scene/scene_builder.hpp"

namespace vdec::bench {

inline constexpr double kElasticBlockSide = 10.0;  // m

inline vdec::Scene elasticBlock(int n) {
  vdec::SceneDefinition s;
  s.title = "benchmark elastic block " + std::to_string(n) + " x " + std::to_string(n) + " crossed cells";
  s.model.rounding = 0.01;
  s.settings.massDamping = 400.0;
  s.settings.stop.cycles = 1;
  const double young = 10e9, poisson = 0.25;
  vdec::BlockMaterial& rock = s.blockMaterials.emplace_back().material;
  rock.name = "rock";
  rock.density = 2500.0;
  rock.bulk = young / (3.0 * (1.0 - 2.0 * poisson));
  rock.shear = young / (2.0 * (1.0 + poisson));
  vdec::BlockDefinition& block = s.blocks.emplace_back();
  block.name = "block";
  block.material = "rock";
  block.vertices = {{0.0, 0.0}, {kElasticBlockSide, 0.0}, {kElasticBlockSide, kElasticBlockSide}, {0.0, kElasticBlockSide}};
  block.zoning.kind = vdec::ZoningDefinition::Kind::Structured;
  block.zoning.nx = block.zoning.ny = n;
  vdec::BoundaryDefinition& base = s.boundaries.emplace_back();
  base.block = "block";
  base.y = {0.0, 0.0};
  base.fix = vdec::DriveX | vdec::DriveY;
  vdec::BoundaryDefinition& top = s.boundaries.emplace_back();
  top.block = "block";
  top.y = {kElasticBlockSide, kElasticBlockSide};
  top.loaded = true;
  top.stress = {0.0, -1e6, 0.0};
  return vdec::buildScene(std::move(s));
}

}  // namespace vdec::bench
