// The test-surface generator: implicit surfaces meshed by CGAL Mesh_3, remeshed isotropically
// onto the exact implicit surface, optionally opened by plane cuts. The only CGAL user of the
// mesh room (compile cost).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Labeled_mesh_domain_3.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <CGAL/Polygon_mesh_processing/clip.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Random.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/facets_in_complex_3_to_triangle_mesh.h>
#include <CGAL/make_mesh_3.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "ricci/mesh/errors.h"
#include "ricci/mesh/generate.h"
#include "ricci/mesh/primitives.h"
#include "ricci/mesh/primitives_detail.h"

namespace ricci {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Vector = Kernel::Vector_3;
using SurfaceMesh = CGAL::Surface_mesh<Point>;
using Domain = CGAL::Labeled_mesh_domain_3<Kernel>;
using Triangulation = CGAL::Mesh_triangulation_3<Domain, CGAL::Default, CGAL::Sequential_tag>::type;
using Complex = CGAL::Mesh_complex_3_in_triangulation_3<Triangulation>;
using Criteria = CGAL::Mesh_criteria_3<Triangulation>;
namespace PMP = CGAL::Polygon_mesh_processing;

constexpr double kTorusR = 1.0;     // major radius of every torus
constexpr double kTorusr = 0.35;    // tube radius
constexpr double kBlend = 0.08;     // smooth-minimum width (length units)

// Smooth minimum -k log sum exp(-d_i / k): C-infinity, equal to min(d) away from junctions.
double smooth_min(const std::vector<double>& d, double k) {
  const double m = *std::min_element(d.begin(), d.end());
  double sum = 0;
  for (double x : d) sum += std::exp(-(x - m) / k);
  return m - k * std::log(sum);
}

// The implicit function (negative inside, roughly a signed distance) and its extent.
struct Shape {
  std::function<double(double, double, double)> f;
  double radius;    // a ball of this radius around the origin contains it with margin
};

Shape make_shape(int genus) {
  if (genus == 0) {
    // Three overlapping spheres: a peanut-like blob, non-convex, with one cap at each x end.
    struct Ball {
      double x, y, z, r;
    };
    const std::array<Ball, 3> balls = {{{-0.7, 0, 0, 0.75}, {0.45, 0.15, 0.05, 0.6},
                                        {0.0, -0.1, 0.55, 0.45}}};
    auto f = [balls](double x, double y, double z) {
      std::vector<double> d;
      for (const auto& b : balls) {
        d.push_back(std::sqrt((x - b.x) * (x - b.x) + (y - b.y) * (y - b.y) +
                              (z - b.z) * (z - b.z)) - b.r);
      }
      return smooth_min(d, 0.15);
    };
    return {f, 2.5};
  }
  // g tori along x, centres 2R apart: neighbouring tubes touch and the smooth minimum fuses them.
  std::vector<double> centres;
  for (int k = 0; k < genus; ++k) centres.push_back(2 * kTorusR * (k - (genus - 1) / 2.0));
  auto f = [centres](double x, double y, double z) {
    std::vector<double> d;
    for (double c : centres) {
      const double q = std::sqrt((x - c) * (x - c) + y * y) - kTorusR;
      d.push_back(std::sqrt(q * q + z * z) - kTorusr);
    }
    return smooth_min(d, kBlend);
  };
  const double x_extent = centres.back() + kTorusR + kTorusr;
  return {f, x_extent + 0.6};
}

// Newton steps along the gradient onto f = 0: remeshed vertices land on the smooth surface.
// With `keep_x` the step is restricted to the plane x = p.x (boundary vertices of a cut).
Point project_onto(const Shape& shape, const Point& p, bool keep_x = false) {
  double x = p.x(), y = p.y(), z = p.z();
  const double h = 1e-6;
  for (int it = 0; it < 10; ++it) {
    const double v = shape.f(x, y, z);
    if (std::abs(v) < 1e-14) break;
    const double gx = keep_x ? 0.0 : (shape.f(x + h, y, z) - shape.f(x - h, y, z)) / (2 * h);
    const double gy = (shape.f(x, y + h, z) - shape.f(x, y - h, z)) / (2 * h);
    const double gz = (shape.f(x, y, z + h) - shape.f(x, y, z - h)) / (2 * h);
    const double g2 = gx * gx + gy * gy + gz * gz;
    if (g2 < 1e-12) break;
    x -= v * gx / g2;
    y -= v * gy / g2;
    z -= v * gz / g2;
  }
  return {x, y, z};
}

SurfaceMesh mesh_implicit(const Shape& shape, std::uint32_t seed) {
  // Mesh_3 draws initial points and some choices from CGAL::get_default_random(), which is
  // seeded from the clock: reseed both generators so a seed fixes the output.
  CGAL::get_default_random() = CGAL::Random(seed);
  CGAL::Random domain_random(seed);
  auto function = [&shape](const Point& p) { return shape.f(p.x(), p.y(), p.z()); };
  namespace params = CGAL::parameters;
  Domain domain = Domain::create_implicit_mesh_domain(
      function, Kernel::Sphere_3(CGAL::ORIGIN, shape.radius * shape.radius),
      params::relative_error_bound = 1e-7, params::p_rng = &domain_random);
  // Only surface criteria: the volume is never refined. Fine enough to carry the geometry; the
  // remeshing sets the final size.
  Criteria criteria(params::facet_angle = 25, params::facet_size = 0.1,
                    params::facet_distance = 0.004);
  Complex complex = CGAL::make_mesh_3<Complex>(domain, criteria, params::no_perturb(),
                                               params::no_exude(), params::manifold());
  SurfaceMesh mesh;
  CGAL::facets_in_complex_3_to_triangle_mesh(complex, mesh);
  if (!CGAL::is_closed(mesh)) throw Error("generate_surface: CGAL Mesh_3 returned an open mesh");
  PMP::orient_to_bound_a_volume(mesh);
  return mesh;
}

// The cut planes x = position, keeping the side where side * (x - position) < 0: hole 1 at the
// +x end, hole 2 at the -x end, each `hole_depth` deep from the closed surface's extreme x.
struct Cut {
  double position;
  double side;
};

std::vector<Cut> cuts_for(const SurfaceMesh& closed, const GenerateOptions& options) {
  if (options.holes == 0) return {};
  const CGAL::Bbox_3 box = PMP::bbox(closed);
  if (options.hole_depth >= box.xmax() - box.xmin()) {
    throw InvalidInputError("generate_surface: hole_depth " + std::to_string(options.hole_depth) +
                            " is not below the surface's x extent");
  }
  std::vector<Cut> cuts = {{box.xmax() - options.hole_depth, 1.0}};
  if (options.holes >= 2) cuts.push_back({box.xmin() + options.hole_depth, -1.0});
  return cuts;
}

void cut(SurfaceMesh& mesh, const std::vector<Cut>& cuts) {
  for (const Cut& c : cuts) {
    PMP::clip(mesh, Kernel::Plane_3(c.side, 0, 0, -c.side * c.position),
              CGAL::parameters::clip_volume(false));
  }
}

// Final placement: interior vertices onto the implicit surface, boundary vertices onto its
// intersection with their cut plane (the remeshing leaves the latter on chords of that curve).
void project_all(SurfaceMesh& mesh, const Shape& shape, const std::vector<Cut>& cuts) {
  for (auto v : mesh.vertices()) {
    if (!mesh.is_border(v)) {
      mesh.point(v) = project_onto(shape, mesh.point(v));
      continue;
    }
    const Point& p = mesh.point(v);
    const Cut* nearest = &cuts.front();
    for (const Cut& c : cuts) {
      if (std::abs(p.x() - c.position) < std::abs(p.x() - nearest->position)) nearest = &c;
    }
    mesh.point(v) = project_onto(shape, Point(nearest->position, p.y(), p.z()), true);
  }
}

double edge_length_for(double area, int faces) {
  return std::sqrt(4 * area / (std::sqrt(3.0) * faces));
}

// One attempt at edge length L: remesh the closed surface onto the implicit surface, cut, then
// clean the cut's slivers with a pass that slides boundary vertices along the boundary.
SurfaceMesh remesh_attempt(const SurfaceMesh& closed, const Shape& shape,
                           const GenerateOptions& options, const std::vector<Cut>& cuts, double L) {
  SurfaceMesh mesh = closed;
  namespace params = CGAL::parameters;
  auto project = [&shape, &mesh](SurfaceMesh::Vertex_index v) {
    return project_onto(shape, mesh.point(v));
  };
  PMP::isotropic_remeshing(faces(mesh), L, mesh,
                           params::number_of_iterations(options.remesh_iterations)
                               .number_of_relaxation_steps(3)
                               .projection_functor(project));
  if (options.holes > 0) {
    cut(mesh, cuts);
    // Put the cut curve on the exact surface first, so the cleanup keeps its neighbours off it.
    project_all(mesh, shape, cuts);
    PMP::isotropic_remeshing(faces(mesh), L, mesh,
                             params::number_of_iterations(3)
                                 .number_of_relaxation_steps(3)
                                 .relax_constraints(true)
                                 .projection_functor(project));
  }
  mesh.collect_garbage();
  project_all(mesh, shape, cuts);
  if (options.holes > 0) {
    // The projection moved the cut curve off its chords, squeezing the triangles along it: a
    // last pass with the (now exact) boundary frozen restores their shape.
    PMP::isotropic_remeshing(faces(mesh), L, mesh,
                             params::number_of_iterations(3)
                                 .number_of_relaxation_steps(3)
                                 .protect_constraints(true)
                                 .projection_functor(project));
    mesh.collect_garbage();
  }
  return mesh;
}

Mesh to_ricci(const SurfaceMesh& mesh) {
  std::vector<Eigen::Vector3d> points;
  std::vector<int> id(mesh.number_of_vertices() + mesh.number_of_removed_vertices(), -1);
  for (auto v : mesh.vertices()) {
    id[v.idx()] = static_cast<int>(points.size());
    const Point& p = mesh.point(v);
    points.emplace_back(p.x(), p.y(), p.z());
  }
  std::vector<std::array<int, 3>> triangles;
  for (auto f : mesh.faces()) {
    std::array<int, 3> t{};
    int k = 0;
    for (auto v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) {
      if (k == 3) throw Error("generate_surface: CGAL returned a non-triangle face");
      t[k++] = id[v.idx()];
    }
    triangles.push_back(t);
  }
  return detail::mesh_from_arrays(points, triangles, "generate_surface");
}

void validate(const GenerateOptions& o) {
  auto fail = [](const std::string& what) { throw InvalidInputError("generate_surface: " + what); };
  if (o.genus < 0 || o.genus > kMaxGeneratedGenus) {
    fail("genus must be 0 to " + std::to_string(kMaxGeneratedGenus) + ", got " +
         std::to_string(o.genus));
  }
  if (o.holes < 0 || o.holes > 2) fail("holes must be 0, 1 or 2, got " + std::to_string(o.holes));
  if (!(o.hole_depth > 0)) fail("hole_depth must be positive");
  if (o.target_faces < 200 || o.target_faces > 2000000) {
    fail("target_faces must be in [200, 2000000], got " + std::to_string(o.target_faces));
  }
  if (o.remesh_iterations < 1 || o.remesh_iterations > 100) fail("remesh_iterations must be in [1, 100]");
}

}  // namespace

Mesh generate_surface(const GenerateOptions& options) {
  validate(options);
  const Shape shape = make_shape(options.genus);
  const SurfaceMesh closed = mesh_implicit(shape, options.seed);

  // Area that survives the cuts, measured on a cut copy of the Mesh_3 output.
  const std::vector<Cut> cuts = cuts_for(closed, options);
  SurfaceMesh opened = closed;
  cut(opened, cuts);
  const double area = PMP::area(opened);
  if (!(area > 0)) throw Error("generate_surface: the cut removed the whole surface");

  // Up to four sizes, keeping the closest to the target among those of the right topology.
  double L = edge_length_for(area, options.target_faces);
  Mesh best;
  double best_error = 1e300;
  std::string failure;
  for (int attempt = 0; attempt < 4; ++attempt) {
    Mesh mesh = to_ricci(remesh_attempt(closed, shape, options, cuts, L));
    const double faces = static_cast<double>(mesh.n_faces());
    const SurfaceTopology t = surface_topology(mesh);
    if (!t.manifold || t.components != 1 || t.genus != options.genus ||
        t.boundary_loops != options.holes) {
      failure = std::to_string(t.components) + " component(s) of genus " +
                std::to_string(t.genus) + " with " + std::to_string(t.boundary_loops) +
                " boundary loop(s)" + (t.manifold ? "" : ", non-manifold");
    } else if (const double error = std::abs(faces / options.target_faces - 1); error < best_error) {
      best_error = error;
      best = std::move(mesh);
    }
    if (best_error < 0.05) break;
    L *= std::sqrt(faces / options.target_faces);
  }
  if (best_error == 1e300) {
    throw Error("generate_surface: CGAL produced " + failure + " instead of " +
                describe_surface(options));
  }
  return best;
}

}  // namespace ricci
