#include <limits>

#include <ricci/mesh/arrays.h>
#include <ricci/topology/slice.h>

#include "arrays.h"
#include "bindings.h"

namespace msp_python {

Atlas make_atlas(const ricci::OneConeAtlasResult& result, nb::object report) {
  const ricci::Mesh& mesh = result.problem.mesh;
  const ricci::AffineAtlas& atlas = result.atlas;
  const auto faces = static_cast<Eigen::Index>(mesh.n_faces());
  Eigen::MatrixX3d V(static_cast<Eigen::Index>(mesh.n_vertices()), 3);
  for (auto v : mesh.vertices()) V.row(v.idx()) = ricci::to_eigen(mesh.point(v)).transpose();
  // Corners in the atlas' order (to-vertex of each of face_halfedges), uv in the central chart.
  Eigen::MatrixX3i F(faces, 3);
  std::vector<double> uv(static_cast<size_t>(faces) * 6, std::numeric_limits<double>::quiet_NaN());
  std::vector<bool> in_domain(static_cast<size_t>(faces));
  const ricci::Chart& central = atlas.charts.front();
  for (auto f : mesh.faces()) {
    const auto hs = ricci::face_halfedges(mesh, f);
    for (int k = 0; k < 3; ++k) F(f.idx(), k) = mesh.to_vertex_handle(hs[k]).idx();
    in_domain[static_cast<size_t>(f.idx())] = atlas.in_domain[static_cast<size_t>(f.idx())] != 0;
    if (central.slot(f.idx()) < 0) continue;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector2d p = atlas.corner_position(0, f.idx(), k);
      uv[static_cast<size_t>(f.idx()) * 6 + static_cast<size_t>(k) * 2] = p.x();
      uv[static_cast<size_t>(f.idx()) * 6 + static_cast<size_t>(k) * 2 + 1] = p.y();
    }
  }
  std::vector<int> cut;
  for (auto e : mesh.edges()) {
    if (!atlas.cut.is_cut_edge[static_cast<size_t>(e.idx())]) continue;
    const auto h = mesh.halfedge_handle(e, 0);
    cut.push_back(mesh.from_vertex_handle(h).idx());
    cut.push_back(mesh.to_vertex_handle(h).idx());
  }
  nb::list transitions;
  for (const ricci::Transition& t : atlas.transitions) {
    nb::dict d;
    d["chart_a"] = t.chart_a;
    d["chart_b"] = t.chart_b;
    d["angle"] = t.motion.angle;
    d["translation"] = nb::make_tuple(t.motion.translation.x(), t.motion.translation.y());
    d["residual"] = t.residual;
    transitions.append(d);
  }
  std::vector<uint8_t> mask(in_domain.begin(), in_domain.end());
  Atlas a;
  a.singularities = report["singularities"];
  a.report = std::move(report);
  a.V = nb::cast(to_numpy(std::move(V)));
  a.F = nb::cast(to_numpy(std::move(F)));
  const size_t cut_rows = cut.size() / 2;
  a.uv = nb::cast(vector_to_numpy(std::move(uv), {static_cast<size_t>(faces), 3, 2}));
  a.in_domain = nb::cast(vector_to_numpy(std::move(mask), {static_cast<size_t>(faces)}))
                    .attr("astype")("bool");
  a.cut_edges = nb::cast(vector_to_numpy(std::move(cut), {cut_rows, 2}));
  a.transitions = std::move(transitions);
  a.cone_vertex = result.problem.cone;
  return a;
}

void bind_atlas(nb::module_& m) {
  nb::class_<Atlas>(m, "Atlas",
                    "A one-cone affine atlas (atlas()). Its mesh (V, F) is the flow's: the input\n"
                    "after valence modification, so it may have more vertices and faces.")
      .def_ro("report", &Atlas::report, "The dict `msp atlas --json` prints.")
      .def_ro("V", &Atlas::V, "(n, 3) float64: vertices of the atlas' mesh.")
      .def_ro("F", &Atlas::F, "(m, 3) int32: faces, corners in the atlas' order.")
      .def_ro("uv", &Atlas::uv,
              "(m, 3, 2) float64: each corner's position in the central chart (NaN for faces\n"
              "the central chart does not hold).")
      .def_ro("in_domain", &Atlas::in_domain,
              "(m,) bool: faces of the spline domain (False on the cone's one-ring).")
      .def_ro("cut_edges", &Atlas::cut_edges,
              "(k, 2) int32: vertex pairs of the cut graph's edges.")
      .def_ro("singularities", &Atlas::singularities, "The report's singularities.")
      .def_ro("transitions", &Atlas::transitions,
              "Transition maps: dicts chart_a, chart_b, angle (radians), translation, residual;\n"
              "the rigid motion takes chart_a's coordinates to chart_b's.")
      .def_ro("cone_vertex", &Atlas::cone_vertex, "Vertex of the cone in V, -1 when none.")
      .def("__repr__", [](const Atlas& a) {
        return "<Atlas " + nb::cast<std::string>(nb::str(a.report["kind"])) + ", " +
               std::to_string(nb::len(a.F)) + " faces, " + std::to_string(nb::len(a.transitions)) +
               " transitions>";
      });
}

}  // namespace msp_python
