#pragma once
// The pieces of the extension module, bound in module.cpp (functions, errors), atlas.cpp (Atlas)
// and spline.cpp (fit, Spline).
#include <nanobind/nanobind.h>
#include <ricci/pipeline/one_cone_atlas.h>

namespace msp_python {

namespace nb = nanobind;

/// A one-cone atlas for Python: plain arrays, lists and the report, built once.
struct Atlas {
  nb::object report, V, F, uv, in_domain, cut_edges, singularities, transitions;
  int cone_vertex = -1;
};

[[nodiscard]] Atlas make_atlas(const ricci::OneConeAtlasResult& result, nb::object report);

/// "auto" -> -1, a non-negative int -> itself. \throw ricci::InvalidInputError otherwise.
[[nodiscard]] int parse_singularity(const nb::object& singularity);

void bind_atlas(nb::module_& m);
void bind_spline(nb::module_& m);

}  // namespace msp_python
