#pragma once
// How far a delivered surface (a triangle soup: the tessellation as written) is from the scan it
// was fitted to, measured both ways by global closest-point queries (AABB trees, ricci's
// soup_distance.h): every scan vertex to the surface, points sampled on the surface to the scan,
// the share of the scan's area the surface reaches, and the distance between the two boundaries.
#include <Eigen/Core>
#include <array>
#include <functional>
#include <memory>
#include <vector>

namespace ricci {
class TriangleSoupDistance;
}

namespace spline {

class KnownSampleDistances;

struct ScanDistanceOptions {
  /// A scan point is covered when the surface passes within this distance, as a fraction of the
  /// scan's bounding-box diagonal.
  double coverage_tolerance = 0.005;
  int threads = 0;  ///< Query threads; 0 = all cores.
  /// By surface triangle, nonzero: left out of the surface-to-scan direction (a patch that caps
  /// a hole of the scan has no scan to be near). Empty: every triangle measured.
  std::vector<char> unmeasured_surface_triangles;
  /// By scan vertex, nonzero: a scan boundary edge with both ends flagged is left out of the
  /// boundary comparison (a small hole the surface caps on purpose). Empty: every edge compared.
  std::vector<char> unmeasured_scan_boundary;
  /// Surface samples measured ahead against the same prepared scan (KnownSampleDistances):
  /// their distances are taken instead of searched again (the same numbers). Null: none.
  const KnownSampleDistances* known_samples = nullptr;
};

/// Distances are absolute (the scan's units); divide by bbox_diagonal for fractions.
struct ScanDistanceReport {
  double bbox_diagonal = 0.0;  ///< Of the scan's vertices.
  /// Every scan vertex to the surface (none left out).
  int scan_points = 0;
  double fit_rms = 0.0, fit_max = 0.0;
  Eigen::Vector3d fit_max_point = Eigen::Vector3d::Zero();  ///< The scan vertex farthest away.
  /// Surface to scan: every surface vertex and every non-degenerate triangle's centroid (of
  /// the measured triangles); surface_points_left_out: those of the unmeasured ones.
  int surface_points = 0;
  int surface_points_left_out = 0;
  double surface_to_scan_p99 = 0.0, surface_to_scan_max = 0.0;
  Eigen::Vector3d surface_to_scan_max_point = Eigen::Vector3d::Zero();
  /// Share of the scan's area within coverage_tolerance of the surface (each scan triangle
  /// weighted by the share of its four samples, corners' centroid and the three points at
  /// barycentric (2/3, 1/6, 1/6), that are covered).
  double coverage = 0.0;
  double coverage_tolerance = 0.0;  ///< Absolute.
  /// Boundary edges (in one triangle only) of each, and the two one-sided distances between the
  /// boundary curves (largest distance of a sample of one, the edges' ends and midpoints, to the
  /// other's edges) and their maximum, the Hausdorff distance. -1 when either side has no
  /// boundary (a closed surface and a closed scan: nothing to compare).
  int scan_boundary_edges = 0, surface_boundary_edges = 0;
  int scan_boundary_edges_left_out = 0;  ///< By unmeasured_scan_boundary (not in the count above).
  double surface_boundary_to_scan_boundary = -1.0, scan_boundary_to_surface_boundary = -1.0;
  double boundary_hausdorff = -1.0;
  /// The boundary sample (of either side) at the Hausdorff distance from the other boundary.
  Eigen::Vector3d boundary_hausdorff_point = Eigen::Vector3d::Zero();
};

/// Measures `surface` (positions, triangles by position index) against the scan (the same).
/// \throw ricci::InvalidInputError for indices out of range, non-finite positions, an empty
///        surface or scan, every surface triangle unmeasured, unmeasured flags of another size
///        (either kind), a coverage tolerance that is not positive, or known_samples (they
///        need a PreparedScan).
[[nodiscard]] ScanDistanceReport measure_against_scan(
    const Eigen::MatrixX3d& surface_positions,
    const std::vector<std::array<int, 3>>& surface_triangles,
    const Eigen::MatrixX3d& scan_positions, const std::vector<std::array<int, 3>>& scan_triangles,
    const ScanDistanceOptions& options = {});

/// The scan's side of measure_against_scan (its positions, triangles and search tree) built
/// once, ahead of the surfaces measured against it: on another thread while a fit has not yet
/// produced a surface, or for several surfaces. Queries are const (several threads may measure).
class PreparedScan {
 public:
  /// \throw ricci::InvalidInputError as measure_against_scan does for the scan.
  PreparedScan(Eigen::MatrixX3d positions, std::vector<std::array<int, 3>> triangles);
  ~PreparedScan();
  PreparedScan(const PreparedScan&) = delete;
  PreparedScan& operator=(const PreparedScan&) = delete;

  [[nodiscard]] const Eigen::MatrixX3d& positions() const { return positions_; }
  [[nodiscard]] const std::vector<std::array<int, 3>>& triangles() const { return triangles_; }
  [[nodiscard]] const ricci::TriangleSoupDistance& tree() const { return *tree_; }

 private:
  Eigen::MatrixX3d positions_;
  std::vector<std::array<int, 3>> triangles_;
  std::unique_ptr<ricci::TriangleSoupDistance> tree_;
};

/// measure_against_scan against a prepared scan: the same report (the same tree), without
/// building the scan's tree.
/// \throw ricci::InvalidInputError as measure_against_scan does for the surface and options,
///        or for known_samples measured on another prepared scan.
[[nodiscard]] ScanDistanceReport measure_against_scan(
    const Eigen::MatrixX3d& surface_positions,
    const std::vector<std::array<int, 3>>& surface_triangles, const PreparedScan& scan,
    const ScanDistanceOptions& options = {});

/// The surface-to-scan direction of measure_against_scan (every vertex of a surface, and every
/// non-degenerate triangle's centroid searched from its first corner's answer) measured ahead,
/// on a surface that shares most of its samples with the one measured later (a fit's surface
/// before its holes are capped): ScanDistanceOptions::known_samples. A vertex sample is known by
/// its position, a centroid by its position and its first corner's, bit for bit, so a known
/// sample's distance is the one the later measure would find.
class KnownSampleDistances {
 public:
  /// Measures every vertex used by `triangles` and every non-degenerate triangle's centroid
  /// against `scan` on `threads` threads (0: all cores). `scan` must be the one the later
  /// measure_against_scan runs on. `stop`, when given, is asked between chunks of samples:
  /// once it returns true the samples measured so far are all that is known (the time left
  /// before the surface measured later is there).
  /// \throw ricci::InvalidInputError as measure_against_scan does for the surface.
  KnownSampleDistances(const Eigen::MatrixX3d& positions,
                       const std::vector<std::array<int, 3>>& triangles, const PreparedScan& scan,
                       int threads = 0, const std::function<bool()>& stop = {});
  ~KnownSampleDistances();
  KnownSampleDistances(KnownSampleDistances&&) noexcept;
  KnownSampleDistances& operator=(KnownSampleDistances&&) noexcept;

  /// The scan this was measured against.
  [[nodiscard]] const PreparedScan& scan() const { return *scan_; }
  /// Vertex samples and centroid samples known.
  [[nodiscard]] std::size_t vertex_count() const;
  [[nodiscard]] std::size_t centroid_count() const;

  struct Tables;  ///< the samples by their points (scan_distance.cpp)
  [[nodiscard]] const Tables& tables() const { return *tables_; }

 private:
  const PreparedScan* scan_ = nullptr;
  std::unique_ptr<Tables> tables_;
};

/// Edges of exactly one triangle (position indices, in triangle order): the soup's boundary.
[[nodiscard]] std::vector<std::array<int, 2>> soup_boundary_edges(
    const std::vector<std::array<int, 3>>& triangles);

}  // namespace spline
