// Loads a spline, pushes a region of it out, and writes the edited surface as binary glTF.
//   edit_spline SPLINE.msp OUT.glb [HEIGHT]
// The region is a ball around the surface point at the middle of the first domain face, of a
// tenth of the bounding-box diagonal; its control points move along the surface normal there by
// HEIGHT (a fraction of the diagonal, default 0.02), weighted smoothly to zero at the ball's
// edge. The surface changes only over the moved functions' supports.
#include <cstdio>
#include <exception>
#include <string>

#include <Eigen/Core>
#include <msp/io/tessellation_io.h>
#include <ricci/mesh/errors.h>
#include <spline/io/spline_file.h>
#include <spline/surface/edit.h>
#include <spline/surface/evaluate.h>
#include <spline/surface/tessellate_surface.h>

int main(int argc, char** argv) {
  if (argc < 3 || argc > 4) {
    std::fprintf(stderr, "usage: edit_spline SPLINE.msp OUT.glb [HEIGHT]\n");
    return 2;
  }
  try {
    spline::SplineSurface surface = spline::load_spline_surface(argv[1]);
    const double height = argc == 4 ? std::stod(argv[3]) : 0.02;

    const Eigen::MatrixX3d& c = surface.spline.control_points;
    const double diagonal = (c.colwise().maxCoeff() - c.colwise().minCoeff()).norm();
    int face = 0;  // the first face the surface shows
    while (!surface.skipped_faces.empty() && surface.skipped_faces[face]) ++face;
    const spline::DomainPoint middle{face, Eigen::Vector3d::Constant(1.0 / 3.0)};
    const spline::SurfaceDifferential at = spline::evaluate_surface(surface, middle);

    const spline::EditReport edit = spline::move_region(surface, at.position, 0.1 * diagonal,
                                                        height * diagonal * at.normal);
    msp::write_tessellation(spline::tessellate_surface(surface, {}), argv[2]);
    std::printf("%s: %zu of %d control points moved, %zu faces changed -> %s\n", argv[1],
                edit.moved_functions.size(), surface.spline.space->function_count(),
                edit.affected_faces.size(), argv[2]);
    return 0;
  } catch (const ricci::Error& e) {  // unreadable or invalid spline file, bad edit
    std::fprintf(stderr, "edit_spline: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "edit_spline: %s\n", e.what());
    return 2;
  }
}
