// Fits a manifold spline to a scan, saves the spline and writes the surface.
//   fit_scan MESH OUT.msp OUT.ply|OUT.obj|OUT.glb [DOMAIN_FACES]
// MESH is any OBJ, OFF, PLY or STL triangle mesh (a connected oriented 2-manifold of any genus).
#include <cstdio>
#include <exception>
#include <string>

#include <msp/io/tessellation_io.h>
#include <ricci/mesh/errors.h>
#include <ricci/mesh/io.h>
#include <spline/io/spline_file.h>
#include <spline/surface/fit_surface.h>

int main(int argc, char** argv) {
  if (argc < 4 || argc > 5) {
    std::fprintf(stderr, "usage: fit_scan MESH OUT.msp OUT.ply|OUT.obj|OUT.glb [DOMAIN_FACES]\n");
    return 2;
  }
  try {
    const ricci::Mesh scan = ricci::read_mesh(argv[1]);

    // The whole job of `msp fit` in one call: simplify the scan to a domain mesh, one-cone
    // affine atlas, DMS spline fitted inside the fairing constraints, the cone's hole capped by
    // a G1 patch, a watertight tessellation and the report's figures.
    spline::FitSurfaceOptions options;
    if (argc == 5) options.domain_faces = std::stoi(argv[4]);
    const spline::FittedSurface fitted = spline::fit_surface(scan, options);

    // The spline itself (evaluated bit for bit the same when loaded again), and the triangles.
    spline::save_spline_surface(fitted.surface, argv[2]);
    msp::write_tessellation(fitted.tessellation, argv[3]);

    std::printf("%s: genus %d, %d control points, fit rms %.3g of the diagonal, %zu triangles, "
                "watertight %s -> %s, %s\n",
                argv[1], fitted.input.genus, fitted.surface.spline.space->function_count(),
                fitted.fit_rms / fitted.bbox_diagonal, fitted.tessellation.triangles.size(),
                fitted.watertight ? "yes" : "no", argv[2], argv[3]);
    return 0;
  } catch (const ricci::Error& e) {  // bad input, unreadable file, failed solve
    std::fprintf(stderr, "fit_scan: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fit_scan: %s\n", e.what());
    return 2;
  }
}
