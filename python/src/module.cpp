// The extension module manifold_splines._core: the library's typed errors as Python exceptions,
// mesh reading, diagnosis, flow, one-cone atlas and uniformization on numpy (V, F) arrays. The
// reports are the dicts the msp tool prints with --json (msp/report). Long calls release the GIL.
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>

#include <msp/report/ricci_reports.h>
#include <ricci/flow/targets.h>
#include <ricci/intrinsic/routed_flow.h>
#include <ricci/mesh/arrays.h>
#include <ricci/mesh/build_mesh.h>
#include <ricci/mesh/diagnose.h>
#include <ricci/mesh/errors.h>
#include <ricci/mesh/io.h>
#include <ricci/topology/slice.h>

#include "arrays.h"
#include "bindings.h"

namespace msp_python {
namespace {

const char* const kArraysName = "(V, F) arrays";

PyObject* error_class = nullptr;
PyObject* io_error_class = nullptr;
PyObject* invalid_input_class = nullptr;
PyObject* topology_error_class = nullptr;
PyObject* infeasible_target_class = nullptr;
PyObject* solver_error_class = nullptr;

// A new exception class manifold_splines.NAME deriving from `bases`, kept in the module.
PyObject* add_exception(nb::module_& m, const char* name, nb::handle bases, const char* doc) {
  const std::string qualified = std::string("manifold_splines.") + name;
  PyObject* type = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, bases.ptr(), nullptr);
  if (!type) throw nb::python_error();
  m.attr(name) = nb::handle(type);  // the module holds a reference, the globals borrow it
  Py_DECREF(type);
  return type;
}

void add_exceptions(nb::module_& m) {
  auto tuple = [](std::initializer_list<PyObject*> items) {
    nb::list list;
    for (PyObject* item : items) list.append(nb::handle(item));
    return nb::tuple(list);
  };
  error_class = add_exception(m, "Error", tuple({PyExc_Exception}),
                              "Base of every error the library raises on purpose.");
  io_error_class = add_exception(m, "IOError", tuple({error_class, PyExc_OSError}),
                                 "A file cannot be read or written, or is malformed.");
  invalid_input_class =
      add_exception(m, "InvalidInputError", tuple({error_class, PyExc_ValueError}),
                    "The input violates a precondition (bad array, NaN, bad option, ...).");
  topology_error_class =
      add_exception(m, "TopologyError", tuple({invalid_input_class}),
                    "The mesh's topology is unsuitable (non-manifold, several components, ...).");
  infeasible_target_class = add_exception(m, "InfeasibleTargetError", tuple({invalid_input_class}),
                                          "A curvature target no metric can reach.");
  solver_error_class = add_exception(m, "SolverError", tuple({error_class, PyExc_RuntimeError}),
                                     "A numerical solve failed or did not converge.");
  nb::register_exception_translator([](const std::exception_ptr& p, void*) {
    try {
      std::rethrow_exception(p);
    } catch (const ricci::TopologyError& e) {
      PyErr_SetString(topology_error_class, e.what());
    } catch (const ricci::InfeasibleTargetError& e) {
      PyErr_SetString(infeasible_target_class, e.what());
    } catch (const ricci::InvalidInputError& e) {
      PyErr_SetString(invalid_input_class, e.what());
    } catch (const ricci::IOError& e) {
      PyErr_SetString(io_error_class, e.what());
    } catch (const ricci::SolverError& e) {
      PyErr_SetString(solver_error_class, e.what());
    } catch (const ricci::Error& e) {
      PyErr_SetString(error_class, e.what());
    }
  });
}

template <class Enum>
Enum parse_enum(const std::string& text, const char* option, std::initializer_list<Enum> values,
                std::string (*name)(Enum)) {
  std::string names;
  for (Enum value : values) {
    if (text == name(value)) return value;
    names += (names.empty() ? "" : ", ") + name(value);
  }
  throw ricci::InvalidInputError(std::string(option) + " must be one of " + names + ", not '" +
                                 text + "'");
}

std::string radii_name(ricci::RadiusInit r) {
  return r == ricci::RadiusInit::mean  ? "mean"
         : r == ricci::RadiusInit::min ? "min"
                                       : "least-squares";
}

ricci::Geometry parse_geometry(const std::string& s) {
  using G = ricci::Geometry;
  return parse_enum<G>(s, "geometry", {G::euclidean, G::hyperbolic, G::spherical},
                       [](G g) { return ricci::to_string(g); });
}

// metric / radii as msp flow, msp atlas and msp uniformize read them (None: the default).
void apply_metric(ricci::FlowOptions& flow, const std::optional<std::string>& metric,
                  const std::optional<std::string>& radii) {
  using S = ricci::Scheme;
  using R = ricci::RadiusInit;
  if (metric) {
    flow.scheme = parse_enum<S>(*metric, "metric",
                                {S::circle_packing, S::inversive_distance, S::combinatorial},
                                [](S s) { return ricci::to_string(s); });
  }
  if (radii)
    flow.radii = parse_enum<R>(*radii, "radii", {R::mean, R::min, R::least_squares}, radii_name);
}

nb::tuple read_mesh(const std::string& path) {
  ricci::VertexFaceArrays arrays;
  {
    nb::gil_scoped_release release;
    arrays = ricci::to_arrays(ricci::read_mesh(path));
  }
  return nb::make_tuple(to_numpy(std::move(arrays.V)), to_numpy(std::move(arrays.F)));
}

nb::object info(nb::handle V, nb::handle F, const std::string& name) {
  const ricci::PolygonSoup soup = soup_from_arrays(V, F, name);
  ricci::MeshDiagnosis diagnosis;
  {
    nb::gil_scoped_release release;
    diagnosis = ricci::diagnose(soup);
  }
  return to_python(msp::mesh_info_json(name, diagnosis));
}

// The soup's input index of each mesh vertex, and the mesh (unreferenced vertices dropped).
ricci::MeshBuildResult build(nb::handle V, nb::handle F, const std::string& name) {
  const ricci::PolygonSoup soup = soup_from_arrays(V, F, name);
  nb::gil_scoped_release release;
  return ricci::build_mesh_with_report(soup);
}

nb::tuple flow(nb::handle V, nb::handle F, const std::string& geometry,
               const std::optional<std::string>& metric, const std::optional<std::string>& radii,
               const std::string& target, double tolerance, int max_iterations,
               const std::string& name) {
  ricci::RoutedFlowOptions routed;
  ricci::FlowOptions& options = routed.flow;
  options.geometry = parse_geometry(geometry);
  if (metric && *metric == "intrinsic-delaunay") {
    routed.route = ricci::FlowRoute::intrinsic_delaunay;
  } else {
    apply_metric(options, metric, radii);
  }
  options.fall_back_to_other_metrics = !metric && !radii;
  options.tolerance = tolerance;
  if (max_iterations > 0) {
    options.max_newton_iterations = options.max_gradient_iterations =
        routed.intrinsic_max_iterations = max_iterations;
  }
  const ricci::MeshBuildResult built = build(V, F, name);
  ricci::RoutedFlowResult run;
  {
    nb::gil_scoped_release release;
    const ricci::Targets targets = ricci::parse_target(target, built.mesh, options.geometry);
    run = ricci::routed_flow(built.mesh, targets, routed);
  }
  const ricci::FlowResult& result = run.flow;
  if (!result.converged()) throw ricci::SolverError(result.message);
  // u by input vertex (NaN for vertices no face uses).
  Eigen::VectorXd u = Eigen::VectorXd::Constant(static_cast<Eigen::Index>(nb::len(V)),
                                                std::numeric_limits<double>::quiet_NaN());
  for (size_t v = 0; v < built.input_vertex.size(); ++v)
    u[built.input_vertex[v]] = result.u[static_cast<Eigen::Index>(v)];
  nb::object report = to_python(msp::flow_report_json(name, built.mesh, options, run));
  return nb::make_tuple(to_numpy(std::move(u)), report);
}

Atlas atlas(nb::handle V, nb::handle F, const nb::object& singularity,
            const std::optional<std::string>& metric, const std::optional<std::string>& radii,
            double tolerance, const std::string& name) {
  ricci::OneConeAtlasOptions options;
  options.singular_vertex = parse_singularity(singularity);
  apply_metric(options.flow, metric, radii);
  options.keep_metric = metric || radii;
  options.flow.tolerance = tolerance;
  const ricci::MeshBuildResult built = build(V, F, name);
  ricci::OneConeAtlasResult result;
  {
    nb::gil_scoped_release release;
    result = ricci::build_one_cone_atlas(built.mesh, options);
  }
  return make_atlas(result, to_python(msp::atlas_report_json(name, built.mesh, result)));
}

nb::object uniformize(nb::handle V, nb::handle F, const std::optional<std::string>& metric,
                      const std::optional<std::string>& radii, double tolerance,
                      const std::string& name) {
  ricci::UniformizeOptions options;
  apply_metric(options.flow, metric, radii);
  options.flow.fall_back_to_other_metrics = !metric && !radii;
  options.flow.tolerance = tolerance;
  const ricci::MeshBuildResult built = build(V, F, name);
  ricci::Uniformization u;
  {
    nb::gil_scoped_release release;
    u = ricci::uniformize(built.mesh, options);
  }
  if (!u.converged()) throw ricci::SolverError("the flow did not converge: " + u.flow.message);
  return to_python(msp::uniformize_report_json(name, built.mesh, u));
}

}  // namespace

int parse_singularity(const nb::object& singularity) {
  if (nb::isinstance<nb::str>(singularity)) {
    if (nb::cast<std::string>(singularity) == "auto") return -1;
  } else if (nb::isinstance<nb::int_>(singularity) && !nb::isinstance<nb::bool_>(singularity)) {
    const long long v = nb::cast<long long>(singularity);
    if (v >= 0 && v <= INT32_MAX) return static_cast<int>(v);
  }
  throw ricci::InvalidInputError("singularity must be \"auto\" or a vertex index, not " +
                                 nb::cast<std::string>(nb::repr(singularity)));
}

}  // namespace msp_python

NB_MODULE(_core, m) {
  using namespace msp_python;
  using namespace nb::literals;
  m.doc() = "Manifold splines: Ricci flow, affine atlases and DMS spline surfaces (C++ core).";
  add_exceptions(m);

  m.def("read_mesh", &read_mesh, "path"_a,
        nb::sig("def read_mesh(path: str) -> tuple[numpy.typing.NDArray[numpy.float64], "
                "numpy.typing.NDArray[numpy.int32]]"),
        "Reads an OBJ, OFF, PLY or STL file (also .gz) as (V, F): V (n, 3) float64, F (m, 3)\n"
        "int32. The same strict reading as the msp tool: polygons triangulated, unreferenced\n"
        "vertices dropped, faces oriented consistently.\n\n"
        "Raises IOError (unreadable, malformed), TopologyError (not a single-component\n"
        "orientable 2-manifold), InvalidInputError (NaN coordinates, degenerate faces).");
  m.def("info", &info, "V"_a, "F"_a, "name"_a = kArraysName,
        nb::sig("def info(V: numpy.typing.ArrayLike, F: numpy.typing.ArrayLike, "
                "name: str = '(V, F) arrays') -> dict"),
        "Describes a mesh as `msp info --json` does (counts, topology, defects, problems);\n"
        "never refuses a mesh for its topology. `name` is the report's \"file\".\n\n"
        "Raises InvalidInputError for arrays of the wrong shape or dtype, or indices out of\n"
        "range.");
  m.def("flow", &flow, "V"_a, "F"_a, nb::kw_only(), "geometry"_a = "euclidean",
        "metric"_a = nb::none(), "radii"_a = nb::none(), "target"_a = "uniform",
        "tolerance"_a = 1e-10, "max_iterations"_a = 0, "name"_a = kArraysName,
        nb::sig("def flow(V: numpy.typing.ArrayLike, F: numpy.typing.ArrayLike, *, "
                "geometry: str = 'euclidean', metric: str | None = None, radii: str | None = "
                "None, target: str = 'uniform', tolerance: float = 1e-10, max_iterations: int = "
                "0, name: str = '(V, F) arrays') -> tuple[numpy.typing.NDArray[numpy.float64], "
                "dict]"),
        "Discrete Ricci flow to a target curvature, as `msp flow --json`: returns (u, report),\n"
        "u the flow variables by vertex of V (NaN where no face uses the vertex) and the\n"
        "report dict. geometry: euclidean|hyperbolic|spherical; metric:\n"
        "circle-packing|inversive-distance|combinatorial|intrinsic-delaunay (None:\n"
        "inversive-distance, falling back to the others and, on a closed surface in E2, to\n"
        "intrinsic-delaunay); radii: mean|min|least-squares; target: uniform|cone:VERTEX|\n"
        "boundary|boundary-loop.\n\n"
        "Raises InvalidInputError / TopologyError for bad meshes or options,\n"
        "InfeasibleTargetError, SolverError when the flow does not converge.");
  m.def("atlas", &atlas, "V"_a, "F"_a, nb::kw_only(), "singularity"_a = "auto",
        "metric"_a = nb::none(), "radii"_a = nb::none(), "tolerance"_a = 1e-10,
        "name"_a = kArraysName,
        nb::sig("def atlas(V: numpy.typing.ArrayLike, F: numpy.typing.ArrayLike, *, "
                "singularity: str | int = 'auto', metric: str | None = None, radii: str | None = "
                "None, tolerance: float = 1e-10, name: str = '(V, F) arrays') -> Atlas"),
        "The one-cone flat metric, cut graph, layout and affine atlas (`msp atlas`).\n"
        "singularity: \"auto\" (least area distortion) or an interior vertex index.\n\n"
        "Raises InvalidInputError / TopologyError for bad input, SolverError when the flow\n"
        "does not converge.");
  m.def("uniformize", &uniformize, "V"_a, "F"_a, nb::kw_only(), "metric"_a = nb::none(),
        "radii"_a = nb::none(), "tolerance"_a = 1e-12, "name"_a = kArraysName,
        nb::sig("def uniformize(V: numpy.typing.ArrayLike, F: numpy.typing.ArrayLike, *, "
                "metric: str | None = None, radii: str | None = None, tolerance: float = 1e-12, "
                "name: str = '(V, F) arrays') -> dict"),
        "The uniformization metric and its geometric structure, as `msp uniformize --json`:\n"
        "Fuchsian generators with Klein matrices (genus >= 2), translations and modulus\n"
        "(torus), the unit-sphere embedding's figures (genus 0).\n\n"
        "Raises InvalidInputError / TopologyError for bad input, SolverError when the flow\n"
        "does not converge.");
  bind_atlas(m);
  bind_spline(m);
}
