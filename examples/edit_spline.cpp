// Edits a manifold spline and writes the edited surface as binary glTF.
//   edit_spline MESH OUT.glb [HEIGHT]
// The spline is fitted to MESH; then the control points are pushed along the surface normal by
// HEIGHT (a fraction of the bounding-box diagonal, default 0.02): the surface swells evenly, as
// smooth as before, since the DMS basis is a partition of unity.
#include <cstdio>
#include <exception>
#include <string>

#include <Eigen/Core>
#include <msp/io/tessellation_io.h>
#include <ricci/mesh/errors.h>
#include <ricci/mesh/io.h>
#include <spline/fit/fit.h>
#include <spline/tessellate/tessellate.h>

namespace {

// The spline to edit. (A saved spline file would be loaded here instead of fitting again.)
spline::ScanFitResult make_spline(const std::string& path) {
  spline::ScanFitOptions options;
  options.domain_faces = 800;
  return spline::fit_scan(ricci::read_mesh(path), options);
}

// Moves the control points of each domain face by `height` along the surface normal at the
// face's centre (the DMS functions are grouped by domain face): an offset surface, to first
// order.
void swell(spline::ManifoldSpline& spline, double height) {
  const spline::ManifoldSplineSpace& space = *spline.space;
  const Eigen::MatrixX3d before = spline.control_points;
  for (int face : space.domain_faces()) {
    const Eigen::Vector3d normal = spline.evaluate(spline::DomainPoint{face}).normal;
    const int first = space.function_index(face, 0);
    for (int k = 0; k < space.functions_per_face(); ++k)
      spline.control_points.row(first + k) = before.row(first + k) + height * normal.transpose();
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3 || argc > 4) {
    std::fprintf(stderr, "usage: edit_spline MESH OUT.glb [HEIGHT]\n");
    return 2;
  }
  try {
    spline::ScanFitResult fit = make_spline(argv[1]);
    const ricci::Mesh& domain = fit.atlas.problem.mesh;
    spline::TessellationOptions sampling;
    sampling.density = 4;
    const spline::Tessellation before = spline::tessellate(fit.spline, domain, sampling);

    const double diagonal = (before.positions.colwise().maxCoeff() -
                             before.positions.colwise().minCoeff()).norm();
    const double height = (argc == 4 ? std::stod(argv[3]) : 0.02) * diagonal;
    swell(fit.spline, height);

    const spline::Tessellation after = spline::tessellate(fit.spline, domain, sampling);
    msp::write_tessellation(after, argv[2]);
    const double moved = (after.positions - before.positions).rowwise().norm().mean();
    std::printf("%s: control points moved by %.3g, surface by %.3g on average -> %s\n", argv[1],
                height, moved, argv[2]);
    return 0;
  } catch (const ricci::Error& e) {
    std::fprintf(stderr, "edit_spline: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "edit_spline: %s\n", e.what());
    return 2;
  }
}
