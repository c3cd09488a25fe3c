#pragma once
// Procedural test meshes: small, exact, CGAL-free surfaces of known topology for unit tests.
// Every mesh is a proper simplicial complex (no repeated edges, every vertex link a cycle or a
// path), consistently oriented: closed meshes have outward normals (positive signed volume),
// planar open meshes lie in z = 0 and are oriented counter-clockwise seen from +z.
#include <cstdint>

#include <Eigen/Core>

#include "ricci/mesh/mesh.h"

namespace ricci {

/// Regular tetrahedron inscribed in the unit sphere. V=4, F=4, genus 0.
[[nodiscard]] Mesh make_tetrahedron();

/// Icosahedron refined `subdivisions` times by midpoint splitting, projected to the sphere of
/// `radius`. V = 10*4^s + 2, F = 20*4^s, genus 0. \throw InvalidInputError if s < 0 or
/// radius <= 0.
[[nodiscard]] Mesh make_icosphere(int subdivisions, double radius = 1.0);

/// Parametric torus ((R + r cos v) cos u, (R + r cos v) sin u, r sin v) sampled on an
/// n_major x n_minor grid. Vertex (i, j) (i along u, j along v) has index i * n_minor + j.
/// Every quad (i,j),(i+1,j),(i+1,j+1),(i,j+1) is split consistently along the diagonal
/// (i,j)-(i+1,j+1), so every vertex has degree 6. F = 2 * n_major * n_minor, genus 1.
/// \pre n_major, n_minor >= 3 (below that the grid is not a simplicial complex), R > r > 0.
/// \throw InvalidInputError otherwise.
[[nodiscard]] Mesh make_torus(int n_major, int n_minor, double R, double r);

/// The nx x ny square grid with opposite sides identified: the torus R^2 / L with lattice
/// L = {a (width, 0) + b (shear, height)}, triangulated as in make_torus (vertex (i, j) has index
/// i * ny + j, the planar position of vertex (i, j) is (i*width/nx + j*shear/ny, j*height/ny), and
/// every cell is split along its (i,j)-(i+1,j+1) diagonal). The 3D embedding is a parametric
/// torus; its own edge lengths are NOT flat: use flat_torus_edge_lengths for the exact flat metric.
/// \pre nx, ny >= 3, width > 0, height > 0. \throw InvalidInputError otherwise.
[[nodiscard]] Mesh make_flat_torus_grid(int nx, int ny, double width, double height,
                                        double shear = 0.0);

/// Edge lengths of the exactly flat metric of make_flat_torus_grid(nx, ny, width, height, shear),
/// indexed by edge index: every vertex has zero Gaussian curvature (its six corner angles sum to
/// 2 pi). \pre `mesh` came from make_flat_torus_grid with the same nx, ny (its vertex indices
/// encode the grid). \throw InvalidInputError if the mesh does not match the grid.
[[nodiscard]] Eigen::VectorXd flat_torus_edge_lengths(const Mesh& mesh, int nx, int ny,
                                                      double width, double height,
                                                      double shear = 0.0);

/// Planar unit disk in z = 0: a centre vertex and `rings` concentric circles, circle k having
/// sectors * k vertices (near-equilateral triangles). One boundary loop (the unit circle, with
/// sectors * rings vertices), genus 0. \pre rings >= 1, sectors >= 3.
[[nodiscard]] Mesh make_disk(int rings, int sectors);

/// Planar annulus inner_radius <= |p| <= outer_radius in z = 0, made of rings + 1 circles; the
/// outer circle has `sectors` vertices and inner circles proportionally fewer (at least 3). Two
/// boundary loops, genus 0. \pre rings >= 1, sectors >= 3, 0 < inner_radius < outer_radius.
[[nodiscard]] Mesh make_annulus(int rings, int sectors, double inner_radius = 0.5,
                                double outer_radius = 1.0);

/// Planar rectangle [0, width] x [0, height] in z = 0 with nx x ny square cells, each split
/// along its lower-left to upper-right diagonal. Vertex (i, j) has index j * (nx + 1) + i.
/// One boundary loop, genus 0. \pre nx, ny >= 1, width, height > 0.
[[nodiscard]] Mesh make_planar_grid(int nx, int ny, double width, double height);

/// Closed genus-g surface: the boundary of a slab of 1 x (2g+1) x 3 cells (thickness 1 cell) with
/// g square through-holes at cells (2k+1, 1), every cell made of `resolution`^3 unit voxels; the
/// voxel faces are split into right isosceles triangles. `smoothing_iterations` Taubin
/// (lambda/mu) steps then round it without shrinking (the topology never changes).
/// genus 0 gives a box. \pre genus >= 0, resolution >= 1, smoothing_iterations >= 0.
[[nodiscard]] Mesh make_genus_slab(int genus, int resolution = 1, int smoothing_iterations = 0);

/// make_genus_slab(genus, resolution) with `holes` disjoint square patches (one cell face each)
/// removed: an open surface of genus `genus` with `holes` boundary loops. Holes go on the top
/// faces of cells (2k, 0), then their bottom faces, then the top and bottom of cells (2k, 2), so
/// 0 <= holes <= 4 (genus + 1). \throw InvalidInputError otherwise.
[[nodiscard]] Mesh make_open_genus(int genus, int holes, int resolution = 1);

/// Moves every interior vertex in its tangent plane (perpendicular to its area-weighted normal)
/// by a random offset of length <= `relative_amplitude` times its shortest incident edge, drawn
/// from a mt19937 seeded with `seed` (same seed, same mesh, on every platform). A move that would
/// flip an incident triangle or make an angle below 5 degrees is skipped. Boundary vertices stay
/// put, so planar meshes stay planar with the same outline. \pre 0 <= relative_amplitude < 0.5.
[[nodiscard]] Mesh make_random_perturbed(Mesh mesh, double relative_amplitude, std::uint32_t seed);

/// Counts the tests and generators check: V, E, F, connected components, boundary loops,
/// Euler characteristic and genus (2 - 2g = chi + b per component; genus is the sum over
/// components), and whether every vertex is manifold.
struct SurfaceTopology {
  int vertices = 0;
  int edges = 0;
  int faces = 0;
  int components = 0;
  int boundary_loops = 0;
  int euler_characteristic = 0;
  int genus = 0;
  bool manifold = true;  ///< OpenMesh is_manifold holds at every vertex.
};

/// Topology of `mesh` (isolated vertices are ignored in the component count).
[[nodiscard]] SurfaceTopology surface_topology(const Mesh& mesh);

/// Signed volume enclosed by a closed mesh (positive when normals point outward).
[[nodiscard]] double signed_volume(const Mesh& mesh);

}  // namespace ricci
