// Fits a manifold spline to a scan and writes the fitted surface.
//   fit_scan MESH OUT.ply|OUT.obj|OUT.glb [DOMAIN_FACES]
// MESH is any OBJ, OFF, PLY or STL triangle mesh (a connected oriented 2-manifold of any genus).
#include <cstdio>
#include <exception>
#include <string>

#include <msp/io/tessellation_io.h>
#include <ricci/mesh/errors.h>
#include <ricci/mesh/io.h>
#include <spline/fit/fit.h>
#include <spline/tessellate/tessellate.h>

int main(int argc, char** argv) {
  if (argc < 3 || argc > 4) {
    std::fprintf(stderr, "usage: fit_scan MESH OUT.ply|OUT.obj|OUT.glb [DOMAIN_FACES]\n");
    return 2;
  }
  try {
    const ricci::Mesh scan = ricci::read_mesh(argv[1]);

    // Simplify the scan to a domain mesh, build its one-cone affine atlas, fit the DMS spline
    // to the scan's points inside the fairing constraints.
    spline::ScanFitOptions options;
    if (argc == 4) options.domain_faces = std::stoi(argv[3]);
    const spline::ScanFitResult fit = spline::fit_scan(scan, options);

    // Sample the spline 4 times per domain edge: a welded triangle mesh with exact normals.
    spline::TessellationOptions sampling;
    sampling.density = 4;
    const spline::Tessellation surface = spline::tessellate(fit.spline, fit.atlas.problem.mesh,
                                                            sampling);
    msp::write_tessellation(surface, argv[2]);

    std::printf("%s: %d domain faces, %d control points, fit rms %.3g, %zu triangles -> %s\n",
                argv[1], static_cast<int>(fit.atlas.problem.mesh.n_faces()),
                static_cast<int>(fit.spline.control_points.rows()), fit.fit.rms_at_parameters,
                surface.triangles.size(), argv[2]);
    return 0;
  } catch (const ricci::Error& e) {  // bad input, unreadable file, failed solve
    std::fprintf(stderr, "fit_scan: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fit_scan: %s\n", e.what());
    return 2;
  }
}
