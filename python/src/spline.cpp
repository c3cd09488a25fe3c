// fit() and the Spline class: a SplineSurface (fitted or loaded) with evaluation, closest points,
// tessellation, editing through a writable view of its control points, the spline file, glTF
// export and the Bezier pieces. Long calls release the GIL.
#include <optional>
#include <string>

#include <msp/io/tessellation_io.h>
#include <msp/report/fit_report.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>
#include <ricci/mesh/arrays.h>
#include <ricci/mesh/build_mesh.h>
#include <ricci/mesh/errors.h>
#include <spline/basis/multi_index.h>
#include <spline/io/spline_file.h>
#include <spline/surface/bezier.h>
#include <spline/surface/closest_point.h>
#include <spline/surface/evaluate.h>
#include <spline/surface/fit_surface.h>
#include <spline/surface/tessellate_surface.h>

#include "arrays.h"
#include "bindings.h"

namespace msp_python {
namespace {

struct Spline {
  spline::SplineSurface surface;
  nb::object report;  ///< fit: the fit report; loaded: the file's header

  [[nodiscard]] int degree() const { return surface.spline.space->degree(); }
};

// The options msp fit reads, with its checks (its messages without the leading "--").
spline::FitSurfaceOptions fit_options(int domain_faces, int degree, std::optional<int> fairness,
                                      double smoothing,
                                      const nb::object& singularity, bool fill_boundaries,
                                      int density, int cone_refinement, double tolerance,
                                      int refine_rounds, double max_deviation, int fold_rounds,
                                      bool adaptive_domain, double small_holes,
                                      bool tracked_parameters) {
  spline::FitSurfaceOptions o;
  o.domain_faces = domain_faces;
  o.degree = degree;
  o.fairness = fairness;
  o.smoothing = smoothing;
  o.singular_vertex = parse_singularity(singularity);
  o.fill_boundaries = fill_boundaries;
  o.density = density;
  o.cone_refinement.levels = cone_refinement;
  o.tolerance = tolerance;
  o.refinement_rounds = refine_rounds;
  o.max_surface_deviation = max_deviation;
  o.fold_rounds = fold_rounds;
  o.adaptive_domain = adaptive_domain;
  o.small_hole_diameter = small_holes;
  o.tracked_parameters = tracked_parameters;
  spline::check_options(o, [](const std::string& field) {
    if (field == "refinement_rounds") return std::string("refine_rounds");
    if (field == "max_surface_deviation") return std::string("max_deviation");
    if (field == "small_hole_diameter") return std::string("small_holes");
    return field;
  });
  return o;
}

Spline fit(nb::handle V, nb::handle F, int domain_faces, int degree, std::optional<int> fairness,
           double smoothing,
           const nb::object& singularity, bool fill_boundaries, int density, int cone_refinement,
           double tolerance, int refine_rounds, double max_deviation, int fold_rounds,
           bool adaptive_domain, double small_holes, bool tracked_parameters,
           const std::string& name) {
  const spline::FitSurfaceOptions options =
      fit_options(domain_faces, degree, fairness, smoothing, singularity, fill_boundaries, density,
                  cone_refinement, tolerance, refine_rounds, max_deviation, fold_rounds,
                  adaptive_domain, small_holes, tracked_parameters);
  const ricci::PolygonSoup soup = soup_from_arrays(V, F, name);
  nlohmann::json report;
  Spline result;
  {
    nb::gil_scoped_release release;
    spline::FittedSurface fitted = spline::fit_surface(ricci::build_mesh(soup), options);
    report = msp::fit_report_json(name, fitted, options);
    result.surface = std::move(fitted.surface);
  }
  result.report = to_python(report);
  return result;
}

std::vector<spline::SurfaceDifferential> evaluate_all(const Spline& s, nb::handle faces,
                                                      nb::handle bary) {
  const std::vector<spline::DomainPoint> points = domain_points(faces, bary);
  nb::gil_scoped_release release;
  return spline::evaluate_surface(s.surface, points);
}

template <class Get>
NumpyArray<double> rows3(const std::vector<spline::SurfaceDifferential>& d, Get get) {
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> m(static_cast<Eigen::Index>(d.size()),
                                                              3);
  for (size_t i = 0; i < d.size(); ++i) m.row(static_cast<Eigen::Index>(i)) = get(d[i]).transpose();
  return to_numpy(std::move(m));
}

template <class Get>
NumpyArray<double> column(const std::vector<spline::SurfaceDifferential>& d, Get get) {
  Eigen::VectorXd v(static_cast<Eigen::Index>(d.size()));
  for (size_t i = 0; i < d.size(); ++i) v[static_cast<Eigen::Index>(i)] = get(d[i]);
  return to_numpy(std::move(v));
}

nb::object evaluate(const Spline& s, nb::handle faces, nb::handle bary, bool derivatives) {
  const auto d = evaluate_all(s, faces, bary);
  using D = spline::SurfaceDifferential;
  if (!derivatives) return nb::cast(rows3(d, [](const D& x) { return x.position; }));
  nb::dict out;
  out["position"] = rows3(d, [](const D& x) { return x.position; });
  out["du"] = rows3(d, [](const D& x) { return x.du; });
  out["dv"] = rows3(d, [](const D& x) { return x.dv; });
  out["duu"] = rows3(d, [](const D& x) { return x.duu; });
  out["duv"] = rows3(d, [](const D& x) { return x.duv; });
  out["dvv"] = rows3(d, [](const D& x) { return x.dvv; });
  out["normal"] = rows3(d, [](const D& x) { return x.normal; });
  Eigen::VectorXi chart(static_cast<Eigen::Index>(d.size()));
  for (size_t i = 0; i < d.size(); ++i) chart[static_cast<Eigen::Index>(i)] = d[i].chart;
  out["chart"] = to_numpy(std::move(chart));
  return out;
}

nb::dict curvatures(const Spline& s, nb::handle faces, nb::handle bary) {
  const auto d = evaluate_all(s, faces, bary);
  using D = spline::SurfaceDifferential;
  nb::dict out;
  out["gaussian"] = column(d, [](const D& x) { return x.curvature.gaussian; });
  out["mean"] = column(d, [](const D& x) { return x.curvature.mean; });
  out["k1"] = column(d, [](const D& x) { return x.curvature.k1; });
  out["k2"] = column(d, [](const D& x) { return x.curvature.k2; });
  return out;
}

nb::dict closest(const Spline& s, nb::handle points, int density) {
  const Eigen::MatrixX3d targets = matrix_n3(points, "points");
  std::vector<spline::ClosestPoint> found;
  {
    nb::gil_scoped_release release;
    spline::ClosestPointOptions options;
    options.density = density;
    found = spline::ClosestPointIndex(s.surface, options).find_all(targets);
  }
  const auto n = static_cast<Eigen::Index>(found.size());
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> position(n, 3), bary(n, 3);
  Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor> parameter(n, 2);
  Eigen::VectorXd distance(n);
  Eigen::VectorXi face(n), fill(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const spline::ClosestPoint& c = found[static_cast<size_t>(i)];
    position.row(i) = c.position.transpose();
    distance[i] = c.distance;
    face[i] = c.location.point.face;
    bary.row(i) = c.location.point.barycentric.transpose();
    fill[i] = c.location.fill;
    parameter.row(i) = c.location.fill_parameter.transpose();
  }
  nb::dict out;
  out["position"] = to_numpy(std::move(position));
  out["distance"] = to_numpy(std::move(distance));
  out["face"] = to_numpy(std::move(face));
  out["bary"] = to_numpy(std::move(bary));
  out["fill"] = to_numpy(std::move(fill));
  out["fill_parameter"] = to_numpy(std::move(parameter));
  return out;
}

spline::Tessellation tessellate_surface(const Spline& s, int density) {
  if (density < 0) throw ricci::InvalidInputError("density must be at least 1 (0: chosen by size)");
  spline::TessellationOptions options;
  options.density =
      density > 0 ? density : spline::default_density(s.surface.spline.space->domain_face_count());
  nb::gil_scoped_release release;
  return spline::tessellate_surface(s.surface, options);
}

nb::tuple tessellate(const Spline& s, int density) {
  spline::Tessellation t = tessellate_surface(s, density);
  const auto m = static_cast<Eigen::Index>(t.triangles.size());
  Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor> F(m, 3);
  // Texture coordinates per corner: a cut vertex has one uv per side of the cut.
  std::vector<double> uv(static_cast<size_t>(m) * 6);
  for (Eigen::Index i = 0; i < m; ++i) {
    const auto& tri = t.triangles[static_cast<size_t>(i)];
    const auto& render = t.render_triangles[static_cast<size_t>(i)];
    for (int k = 0; k < 3; ++k) {
      F(i, k) = tri[static_cast<size_t>(k)];
      uv[static_cast<size_t>(i * 6 + k * 2)] = t.uvs(render[static_cast<size_t>(k)], 0);
      uv[static_cast<size_t>(i * 6 + k * 2 + 1)] = t.uvs(render[static_cast<size_t>(k)], 1);
    }
  }
  Eigen::MatrixX3d normals = msp::tessellation_normals(t);
  return nb::make_tuple(to_numpy(std::move(t.positions)), to_numpy(std::move(F)),
                        to_numpy(std::move(normals)),
                        vector_to_numpy(std::move(uv), {static_cast<size_t>(m), 3, 2}));
}

void to_glb(const Spline& s, const std::string& path, int density) {
  const spline::Tessellation t = tessellate_surface(s, density);
  nb::gil_scoped_release release;
  msp::write_tessellation(t, path);
}

nb::dict bezier(const Spline& s) {
  spline::BezierExport e;
  {
    nb::gil_scoped_release release;
    e = spline::bezier_patches(s.surface);
  }
  const size_t p = e.patches.size();
  const size_t m = static_cast<size_t>((e.degree + 1) * (e.degree + 2) / 2);
  std::vector<int> face(p), vertices(p * 3);
  std::vector<double> corners(p * 9), control(p * m * 3);
  for (size_t i = 0; i < p; ++i) {
    const spline::BezierPatch& patch = e.patches[i];
    face[i] = patch.face;
    for (size_t k = 0; k < 3; ++k) {
      vertices[i * 3 + k] = patch.vertices[k];
      // corners[i, k] = corner k's barycentric coordinates (column k of the matrix).
      for (size_t c = 0; c < 3; ++c)
        corners[i * 9 + k * 3 + c] =
            patch.corners(static_cast<Eigen::Index>(c), static_cast<Eigen::Index>(k));
    }
    for (size_t r = 0; r < m; ++r)
      for (size_t c = 0; c < 3; ++c)
        control[(i * m + r) * 3 + c] =
            patch.control_points(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c));
  }
  std::vector<int> betas;
  for (const auto& beta : spline::multi_indices(e.degree))
    for (int k = 0; k < 3; ++k) betas.push_back(beta[k]);
  nb::dict out;
  out["degree"] = e.degree;
  out["faces"] = e.faces;
  out["multi_indices"] = vector_to_numpy(std::move(betas), {m, 3});
  out["face"] = vector_to_numpy(std::move(face), {p});
  out["vertices"] = vector_to_numpy(std::move(vertices), {p, 3});
  out["corners"] = vector_to_numpy(std::move(corners), {p, 3, 3});
  out["control_points"] = vector_to_numpy(std::move(control), {p, m, 3});
  return out;
}

nb::dict header_dict(const spline::SplineFileHeader& h, const std::string& path) {
  nb::dict d, provenance;
  for (const auto& [key, value] : h.provenance) provenance[key.c_str()] = value;
  d["spline"] = path;
  d["version"] = h.version;
  d["degree"] = h.degree;
  d["vertices"] = h.vertices;
  d["faces"] = h.faces;
  d["charts"] = h.charts;
  d["transitions"] = h.transitions;
  d["control_points"] = h.control_points;
  d["fills"] = h.fills;
  d["open_rims"] = h.open_rims;
  d["singular_vertex"] = h.singular_vertex;
  d["provenance"] = provenance;
  return d;
}

Spline load(const std::string& path) {
  spline::SplineFile file;
  {
    nb::gil_scoped_release release;
    file = spline::read_spline_file(path);
  }
  Spline s;
  s.surface = std::move(file.surface);
  s.report = header_dict(file.header, path);
  return s;
}

void save(const Spline& s, const std::string& path) {
  nb::gil_scoped_release release;
  spline::save_spline_surface(s.surface, path, {{"tool", "manifold_splines"}});
}

NumpyArray<int> shown_faces(const Spline& s) {
  std::vector<int> faces;
  for (int f : s.surface.spline.space->domain_faces()) {
    const auto skipped = s.surface.skipped_faces;
    if (skipped.empty() || !skipped[static_cast<size_t>(f)]) faces.push_back(f);
  }
  const size_t n = faces.size();
  return vector_to_numpy(std::move(faces), {n});
}

}  // namespace

void bind_spline(nb::module_& m) {
  using namespace nb::literals;
  static const std::string evaluate_doc =
      "Positions (n, 3) of the surface at domain points; with derivatives, a dict of\n"
      "position, du, dv, duu, duv, dvv, normal (n, 3) and chart (n,), the derivatives in that\n"
      "chart's coordinates. faces (n,) integers: domain faces the surface shows\n"
      "(shown_faces()); bary (n, 3) floats: barycentric coordinates in them (each >= -1e-6,\n"
      "summing to 1).\nRaises InvalidInputError on bad arrays or points.";
  nb::class_<Spline>(m, "Spline",
                     "A manifold spline surface (fit() or Spline.load()): the spline over its\n"
                     "domain mesh and the patches capping its holes.")
      .def_ro("report", &Spline::report,
              "fit(): the dict `msp fit --json` writes; Spline.load(): the file's header.")
      .def_prop_ro("degree", &Spline::degree, "Degree of the DMS spline.")
      .def_prop_ro(
          "domain",
          [](const Spline& s) {
            ricci::VertexFaceArrays a = ricci::to_arrays(s.surface.domain);
            return nb::make_tuple(to_numpy(std::move(a.V)), to_numpy(std::move(a.F)));
          },
          nb::for_getter(nb::sig("def domain(self) -> tuple[numpy.typing.NDArray["
                                 "numpy.float64], numpy.typing.NDArray[numpy.int32]]")),
          "(V, F) of the domain mesh (the simplified scan the spline is built on).")
      .def_prop_ro(
          "singular_vertex", [](const Spline& s) { return s.surface.singular_vertex; },
          "Domain vertex of the extraordinary point, -1 when there is none.")
      .def("shown_faces", &shown_faces,
           "Domain faces where the spline is shown and evaluate() accepts points, ascending.")
      .def_prop_rw(
          "control_points",
          [](Spline& s) {
            Eigen::MatrixX3d& c = s.surface.spline.control_points;
            const size_t shape[2] = {static_cast<size_t>(c.rows()), 3};
            const int64_t strides[2] = {1, static_cast<int64_t>(c.rows())};
            return nb::ndarray<nb::numpy, double, nb::ndim<2>>(c.data(), 2, shape, nb::handle(),
                                                               strides);
          },
          [](Spline& s, nb::handle value) {
            Eigen::MatrixX3d c = matrix_n3(value, "control_points");
            if (c.rows() != s.surface.spline.control_points.rows()) {
              throw ricci::InvalidInputError(
                  "control_points must have " +
                  std::to_string(s.surface.spline.control_points.rows()) + " rows");
            }
            if (!c.allFinite()) throw ricci::InvalidInputError("control_points must be finite");
            s.surface.spline.control_points = std::move(c);
          },
          nb::rv_policy::reference_internal,
          "(N, 3) float64, a writable view of the spline's control points: edit it in place\n"
          "and evaluate() / tessellate() / save() see the edit (the fill patches are not\n"
          "refitted). Assigning an (N, 3) array replaces them.")
      .def("evaluate", &evaluate, "faces"_a, "bary"_a, "derivatives"_a = false,
           nb::sig("def evaluate(self, faces: numpy.typing.ArrayLike, bary: "
                   "numpy.typing.ArrayLike, derivatives: bool = False) -> "
                   "numpy.typing.NDArray[numpy.float64] | dict"),
           evaluate_doc.c_str())
      .def(
          "normals",
          [](const Spline& s, nb::handle faces, nb::handle bary) {
            return rows3(evaluate_all(s, faces, bary),
                         [](const spline::SurfaceDifferential& x) { return x.normal; });
          },
          "faces"_a, "bary"_a,
          nb::sig("def normals(self, faces: numpy.typing.ArrayLike, bary: "
                  "numpy.typing.ArrayLike) -> numpy.typing.NDArray[numpy.float64]"),
          "Unit normals (n, 3) (du x dv; zero rows where the parametrisation is singular).")
      .def("curvatures", &curvatures, "faces"_a, "bary"_a,
           nb::sig("def curvatures(self, faces: numpy.typing.ArrayLike, bary: "
                   "numpy.typing.ArrayLike) -> dict[str, numpy.typing.NDArray[numpy.float64]]"),
           "Gaussian, mean and principal curvatures (k1 >= k2), each (n,): a dict with keys\n"
           "gaussian, mean, k1, k2 (sphere of radius R, outward normal: K = 1/R^2, H = -1/R).")
      .def("closest", &closest, "points"_a, "density"_a = 4,
           nb::sig("def closest(self, points: numpy.typing.ArrayLike, density: int = 4) -> "
                   "dict[str, numpy.typing.NDArray]"),
           "Closest points of the surface (spline and patches) to points (n, 3): a dict of\n"
           "position (n, 3), distance (n,), face (n,) and bary (n, 3) on the spline (face -1\n"
           "on a patch), fill (n,) and fill_parameter (n, 2) on a patch (fill -1 on the\n"
           "spline). density: the candidate search's tessellation (finer: safer).")
      .def("tessellate", &tessellate, "density"_a = 0,
           nb::sig("def tessellate(self, density: int = 0) -> tuple[numpy.typing.NDArray["
                   "numpy.float64], numpy.typing.NDArray[numpy.int32], numpy.typing.NDArray["
                   "numpy.float64], numpy.typing.NDArray[numpy.float64]]"),
           "Watertight tessellation (spline and patches welded) as (V, F, N, UV): V (n, 3),\n"
           "F (m, 3), unit normals N (n, 3), UV (m, 3, 2) central-chart coordinates per\n"
           "corner (a vertex on a cut has one per side). density: samples per domain edge - 1\n"
           "(0: msp fit's choice for the domain's size).")
      .def("to_glb", &to_glb, "path"_a, "density"_a = 0,
           "Writes the tessellation as binary glTF (atomically), as `msp tessellate` does.\n"
           "Raises IOError when it cannot be written.")
      .def("save", &save, "path"_a,
           "Writes the spline file (.msp, atomically); Spline.load() reads it back evaluating\n"
           "bit for bit like this surface. Raises IOError.")
      .def_static("load", &load, "path"_a,
                  "Reads a spline file (msp fit --spline, Spline.save()).\n"
                  "Raises IOError (unreadable, malformed) or InvalidInputError (contents).")
      .def("bezier_patches", &bezier,
           "The spline's exact polynomial pieces as triangular Bezier patches (docs/bezier.md):\n"
           "a dict of degree, faces, multi_indices (k, 3), and per patch face (P,), vertices\n"
           "(P, 3), corners (P, 3, 3) (corner k's barycentric coordinates in its face) and\n"
           "control_points (P, k, 3) in multi_indices order.")
      .def("__repr__", [](const Spline& s) {
        return "<Spline degree " + std::to_string(s.degree()) + ", " +
               std::to_string(s.surface.spline.space->domain_face_count()) + " domain faces, " +
               std::to_string(s.surface.spline.control_points.rows()) + " control points>";
      });

  m.def("fit", &fit, "V"_a, "F"_a, nb::kw_only(), "domain_faces"_a = 2000, "degree"_a = 3,
        "fairness"_a = nb::none(), "smoothing"_a = spline::FitSurfaceOptions{}.smoothing,
        "singularity"_a = "auto", "fill_boundaries"_a = false, "density"_a = 0,
        "cone_refinement"_a = spline::FitSurfaceOptions{}.cone_refinement.levels,
        "tolerance"_a = 0.0, "refine_rounds"_a = spline::FitSurfaceOptions{}.refinement_rounds,
        "max_deviation"_a = spline::FitSurfaceOptions{}.max_surface_deviation,
        "fold_rounds"_a = spline::FitSurfaceOptions{}.fold_rounds, "adaptive_domain"_a = false,
        "small_holes"_a = spline::FitSurfaceOptions{}.small_hole_diameter,
        "tracked_parameters"_a = false, "name"_a = "(V, F) arrays",
        nb::sig("def fit(V: numpy.typing.ArrayLike, F: numpy.typing.ArrayLike, *, "
                "domain_faces: int = 2000, degree: int = 3, fairness: int | None = None, "
                "smoothing: float = 0.0001, singularity: str | int = 'auto', "
                "fill_boundaries: bool = False, "
                "density: int = 0, cone_refinement: int = 2, tolerance: float = 0.0, "
                "refine_rounds: int = 1, max_deviation: float = 0.05, fold_rounds: int = 4, "
                "adaptive_domain: bool = False, small_holes: float = 0.002, "
                "tracked_parameters: bool = False, name: str = '(V, F) arrays') -> Spline"),
        "The whole scan-to-surface job of `msp fit` (spline::fit_surface): simplify to\n"
        "domain_faces, one-cone atlas, DMS spline of `degree` fitted inside the fairing\n"
        "constraints of order `fairness` (-1: none; None: 1 from degree 3, 0 below) with\n"
        "thin-plate weight `smoothing`, holes\n"
        "capped by G1 patches (boundaries too with fill_boundaries). Options as msp fit's\n"
        "(singularity: \"auto\" or an interior vertex; tolerance, refine_rounds,\n"
        "max_deviation, fold_rounds, adaptive_domain, small_holes and tracked_parameters as\n"
        "--tolerance, --refine-rounds, --max-deviation, --fold-rounds, --adaptive-domain,\n"
        "--small-holes, --tracked-parameters).\n"
        "Returns the Spline;\n"
        "its report is the\n"
        "dict `msp fit --json` writes, `name` its \"mesh\".\n\n"
        "Raises InvalidInputError / TopologyError for bad arrays, meshes or options;\n"
        "SolverError when the flow does not converge.");
}

}  // namespace msp_python
