// Unstructured zoning of a polygonal block by CGAL's constrained Delaunay refinement (Ruppert and
// Shewchuk's algorithm): quality triangles whose smallest angle is bounded below, no side longer
// than the maximum edge length. Kept in its own file because CGAL's templates are slow to compile.
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <map>

#include "geometry/zoning.hpp"

namespace vdec {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_2<Kernel>;
using FaceBase = CGAL::Delaunay_mesh_face_base_2<Kernel>;
using Structure = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
using Triangulation = CGAL::Constrained_Delaunay_triangulation_2<Kernel, Structure>;
using Criteria = CGAL::Delaunay_mesh_size_criteria_2<Triangulation>;

}  // namespace

Mesh delaunayMesh(const std::vector<Vec2>& outline, double maxEdge) {
  Triangulation cdt;
  std::vector<Triangulation::Vertex_handle> corners;
  for (const Vec2& p : outline) corners.push_back(cdt.insert(Triangulation::Point(p.x, p.y)));
  for (std::size_t i = 0; i < corners.size(); ++i) cdt.insert_constraint(corners[i], corners[(i + 1) % corners.size()]);
  // Shape bound B = circumradius / shortest side = 0.125 ... CGAL's first criterion is the upper
  // bound on 1 / (4 sin^2 theta_min): 0.125 gives theta_min = 20.7 degrees, the largest bound
  // the refinement is guaranteed to reach.
  CGAL::refine_Delaunay_mesh_2(cdt, Criteria(0.125, maxEdge));
  Mesh mesh;
  std::map<Triangulation::Vertex_handle, int> index;
  auto id = [&](Triangulation::Vertex_handle v) {
    auto [it, fresh] = index.emplace(v, static_cast<int>(mesh.nodes.size()));
    if (fresh) mesh.nodes.push_back({v->point().x(), v->point().y()});
    return it->second;
  };
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    if (!f->is_in_domain()) continue;
    // CGAL orders face vertices counter-clockwise.
    mesh.triangles.push_back({id(f->vertex(0)), id(f->vertex(1)), id(f->vertex(2))});
  }
  return mesh;
}

}  // namespace vdec
