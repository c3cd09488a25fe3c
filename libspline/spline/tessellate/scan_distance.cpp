#include "spline/tessellate/scan_distance.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <optional>
#include <unordered_map>
#include <string>
#include <utility>

#include <Eigen/Geometry>

#include "ricci/mesh/errors.h"
#include "ricci/mesh/soup_distance.h"
#include "ricci/util/edge_key.h"
#include "ricci/util/hash.h"
#include "spline/tessellate/parallel_for.h"

namespace spline {
namespace {

// Distances of every row of `points` to `tree`, in parallel (queries on a const tree).
template <class Tree>
Eigen::VectorXd parallel_distances(const Tree& tree, const Eigen::MatrixX3d& points, int threads) {
  Eigen::VectorXd out(points.rows());
  parallel_for(static_cast<std::size_t>(points.rows()), threads, [&](std::size_t i) {
    const auto row = static_cast<Eigen::Index>(i);
    out[row] = tree.closest(points.row(row).transpose()).distance;
  });
  return out;
}

Eigen::MatrixX3d to_rows(const std::vector<Eigen::Vector3d>& points) {
  Eigen::MatrixX3d out(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i)
    out.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  return out;
}

// Nearest points on `tree` of every row of `points`, in parallel (queries on a const tree);
// hint(i), when not null, is the tree's answer for a point near row i, where the search starts
// (the same distances, found faster than from the tree's nearest-vertex look-up).
template <class Hint>
std::vector<ricci::SoupHit> closest_hits(const ricci::TriangleSoupDistance& tree,
                                         const Eigen::MatrixX3d& points, int threads,
                                         const Hint& hint) {
  std::vector<ricci::SoupHit> hits(static_cast<std::size_t>(points.rows()));
  parallel_for(hits.size(), threads, [&](std::size_t i) {
    const Eigen::Vector3d query = points.row(static_cast<Eigen::Index>(i)).transpose();
    const ricci::SoupHit* start = hint(i);
    hits[i] = start ? tree.closest(query, *start) : tree.closest(query);
  });
  return hits;
}

std::vector<ricci::SoupHit> closest_hits(const ricci::TriangleSoupDistance& tree,
                                         const Eigen::MatrixX3d& points, int threads) {
  return closest_hits(tree, points, threads,
                      [](std::size_t) -> const ricci::SoupHit* { return nullptr; });
}

Eigen::VectorXd distances_of(const std::vector<ricci::SoupHit>& hits) {
  Eigen::VectorXd out(static_cast<Eigen::Index>(hits.size()));
  for (std::size_t i = 0; i < hits.size(); ++i)
    out[static_cast<Eigen::Index>(i)] = hits[i].distance;
  return out;
}

// The points measured on the surface: the vertices of the measured triangles, and their
// non-degenerate centroids, each with the row in `vertices` of its triangle's first corner.
struct SurfaceSamples {
  Eigen::MatrixX3d vertices, centroids;
  std::vector<int> centroid_corner;
  int left_out = 0;  ///< Samples of the unmeasured triangles (vertices no measured one uses).
};

SurfaceSamples surface_samples(const Eigen::MatrixX3d& positions,
                               const std::vector<std::array<int, 3>>& triangles,
                               const std::vector<char>& unmeasured) {
  const auto measured = [&unmeasured](std::size_t t) {
    return unmeasured.empty() || !unmeasured[t];
  };
  std::vector<char> used(static_cast<std::size_t>(positions.rows()), 0);  // 1 any, 2 measured
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    for (int v : triangles[t]) {
      char& u = used[static_cast<std::size_t>(v)];
      u = std::max<char>(u, measured(t) ? 2 : 1);
    }
  }
  SurfaceSamples out;
  std::vector<int> row(used.size(), -1);
  std::vector<Eigen::Vector3d> points;
  for (Eigen::Index v = 0; v < positions.rows(); ++v) {
    const char u = used[static_cast<std::size_t>(v)];
    if (u == 2) {
      row[static_cast<std::size_t>(v)] = static_cast<int>(points.size());
      points.emplace_back(positions.row(v).transpose());
    }
    out.left_out += u == 1;
  }
  out.vertices = to_rows(points);
  points.clear();
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const auto& t = triangles[i];
    const Eigen::Vector3d a = positions.row(t[0]), b = positions.row(t[1]), c = positions.row(t[2]);
    if (!((b - a).cross(c - a).norm() > 0.0)) continue;
    if (measured(i)) {
      points.push_back((a + b + c) / 3.0);
      out.centroid_corner.push_back(row[static_cast<std::size_t>(t[0])]);
    } else {
      ++out.left_out;
    }
  }
  out.centroids = to_rows(points);
  return out;
}

void check_indices(const Eigen::MatrixX3d& positions,
                   const std::vector<std::array<int, 3>>& triangles, const char* what) {
  if (triangles.empty()) throw ricci::InvalidInputError(std::string(what) + ": no triangle");
  for (const auto& t : triangles) {
    for (int v : t) {
      if (v < 0 || v >= positions.rows()) {
        throw ricci::InvalidInputError(std::string(what) + ": index " + std::to_string(v) +
                                       " out of range");
      }
      if (!positions.row(v).allFinite()) {
        throw ricci::InvalidInputError(std::string(what) + ": position " + std::to_string(v) +
                                       " is not finite");
      }
    }
  }
}

// The ends and midpoint of every edge.
Eigen::MatrixX3d edge_samples(const Eigen::MatrixX3d& positions,
                              const std::vector<std::array<int, 2>>& edges) {
  Eigen::MatrixX3d out(static_cast<Eigen::Index>(3 * edges.size()), 3);
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const Eigen::RowVector3d a = positions.row(edges[e][0]), b = positions.row(edges[e][1]);
    const auto row = static_cast<Eigen::Index>(3 * e);
    out.row(row) = a;
    out.row(row + 1) = 0.5 * (a + b);
    out.row(row + 2) = b;
  }
  return out;
}

}  // namespace

std::vector<std::array<int, 2>> soup_boundary_edges(
    const std::vector<std::array<int, 3>>& triangles) {
  // Undirected edges sorted, so that an edge's copies are adjacent.
  std::vector<std::uint64_t> edges;
  edges.reserve(3 * triangles.size());
  for (const auto& t : triangles)
    for (int k = 0; k < 3; ++k) edges.push_back(ricci::undirected_edge_key(t[k], t[(k + 1) % 3]));
  std::sort(edges.begin(), edges.end());
  // The keys that occur once (sorted); a closed soup has none and is done.
  std::vector<std::uint64_t> singles;
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i + 1;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    if (j - i == 1) singles.push_back(edges[i]);
    i = j;
  }
  std::vector<std::array<int, 2>> out;
  if (singles.empty()) return out;
  const auto single = [&singles](std::uint64_t e) {
    return std::binary_search(singles.begin(), singles.end(), e);
  };
  for (const auto& t : triangles) {
    for (int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      if (a != b && single(ricci::undirected_edge_key(a, b))) out.push_back({a, b});
    }
  }
  return out;
}

namespace {

// The checks of the surface and the options (the scan's: check_indices).
void check_surface(const Eigen::MatrixX3d& surface_positions,
                   const std::vector<std::array<int, 3>>& surface_triangles,
                   const ScanDistanceOptions& options) {
  check_indices(surface_positions, surface_triangles, "surface");
  if (!(options.coverage_tolerance > 0.0)) {
    throw ricci::InvalidInputError("coverage tolerance must be positive");
  }
  const std::vector<char>& unmeasured = options.unmeasured_surface_triangles;
  if (!unmeasured.empty() && unmeasured.size() != surface_triangles.size()) {
    throw ricci::InvalidInputError("unmeasured_surface_triangles has " +
                                   std::to_string(unmeasured.size()) + " flags for " +
                                   std::to_string(surface_triangles.size()) + " triangles");
  }
}

}  // namespace

// Samples by the bits of their points: a vertex by its position, a centroid by its position and
// its first corner's (the corner's answer is where its search starts).
struct KnownSampleDistances::Tables {
  using VertexKey = std::array<std::uint64_t, 3>;
  using CentroidKey = std::array<std::uint64_t, 6>;
  static VertexKey vertex_key(const Eigen::MatrixX3d& rows, Eigen::Index i) {
    VertexKey k;
    for (int c = 0; c < 3; ++c) {
      const double x = rows(i, c);
      std::memcpy(&k[static_cast<std::size_t>(c)], &x, sizeof x);
    }
    return k;
  }
  static CentroidKey centroid_key(const Eigen::MatrixX3d& centroids, Eigen::Index i,
                                  const Eigen::MatrixX3d& vertices, Eigen::Index corner) {
    const VertexKey a = vertex_key(centroids, i), b = vertex_key(vertices, corner);
    return {a[0], a[1], a[2], b[0], b[1], b[2]};
  }
  std::unordered_map<VertexKey, ricci::SoupHit, ricci::WordsHash> vertices;
  std::unordered_map<CentroidKey, double, ricci::WordsHash> centroids;
};

namespace {

// The surface-to-scan answers of `samples`: each vertex's hit on the scan, each centroid's
// distance (searched from its first corner's hit); those `known` holds taken from it. With
// `stop`: the vertices measured before it said so (a prefix) and the centroids of theirs.
struct SampleHits {
  std::vector<ricci::SoupHit> vertices;
  Eigen::VectorXd centroids;
  std::size_t vertices_done = 0;
  std::vector<char> centroid_done;
};

SampleHits surface_to_scan(const SurfaceSamples& samples, const ricci::TriangleSoupDistance& scan,
                           int threads, const KnownSampleDistances::Tables* known,
                           const std::function<bool()>& stop = {}) {
  using Tables = KnownSampleDistances::Tables;
  SampleHits out;
  out.vertices.resize(static_cast<std::size_t>(samples.vertices.rows()));
  out.vertices_done = parallel_for_until(out.vertices.size(), threads, stop, [&](std::size_t i) {
    const auto row = static_cast<Eigen::Index>(i);
    if (known) {
      const auto it = known->vertices.find(Tables::vertex_key(samples.vertices, row));
      if (it != known->vertices.end()) {
        out.vertices[i] = it->second;
        return;
      }
    }
    out.vertices[i] = scan.closest(samples.vertices.row(row).transpose());
  });
  out.centroids = Eigen::VectorXd::Zero(samples.centroids.rows());
  out.centroid_done.assign(static_cast<std::size_t>(samples.centroids.rows()), 0);
  parallel_for_until(out.centroid_done.size(), threads, stop, [&](std::size_t i) {
    const auto row = static_cast<Eigen::Index>(i);
    const int corner = samples.centroid_corner[i];
    if (static_cast<std::size_t>(corner) >= out.vertices_done) return;
    out.centroid_done[i] = 1;
    if (known) {
      const auto it = known->centroids.find(
          Tables::centroid_key(samples.centroids, row, samples.vertices, corner));
      if (it != known->centroids.end()) {
        out.centroids[row] = it->second;
        return;
      }
    }
    out.centroids[row] = scan.closest(samples.centroids.row(row).transpose(),
                                      out.vertices[static_cast<std::size_t>(corner)])
                             .distance;
  });
  return out;
}

// measure_against_scan with both trees built (the scan's checked).
ScanDistanceReport measure_with_trees(const Eigen::MatrixX3d& surface_positions,
                                      const std::vector<std::array<int, 3>>& surface_triangles,
                                      const ricci::TriangleSoupDistance& surface,
                                      const Eigen::MatrixX3d& scan_positions,
                                      const std::vector<std::array<int, 3>>& scan_triangles,
                                      const ricci::TriangleSoupDistance& scan,
                                      const ScanDistanceOptions& options) {
  const std::vector<char>& unmeasured = options.unmeasured_surface_triangles;
  const std::vector<char>& unmeasured_rim = options.unmeasured_scan_boundary;
  if (!unmeasured_rim.empty() &&
      static_cast<Eigen::Index>(unmeasured_rim.size()) != scan_positions.rows()) {
    throw ricci::InvalidInputError("unmeasured_scan_boundary has " +
                                   std::to_string(unmeasured_rim.size()) + " flags for " +
                                   std::to_string(scan_positions.rows()) + " scan vertices");
  }
  ScanDistanceReport report;
  report.bbox_diagonal =
      (scan_positions.colwise().maxCoeff() - scan_positions.colwise().minCoeff()).norm();
  report.coverage_tolerance = options.coverage_tolerance * report.bbox_diagonal;

  // Every scan vertex to the surface.
  const std::vector<ricci::SoupHit> fit_hits =
      closest_hits(surface, scan_positions, options.threads);
  const Eigen::VectorXd fit = distances_of(fit_hits);
  report.scan_points = static_cast<int>(fit.size());
  Eigen::Index farthest = 0;
  report.fit_max = fit.maxCoeff(&farthest);
  report.fit_max_point = scan_positions.row(farthest).transpose();
  report.fit_rms = std::sqrt(fit.squaredNorm() / static_cast<double>(fit.size()));

  // The surface back to the scan: the vertices, then the centroids (searched from a corner's).
  const SurfaceSamples samples = surface_samples(surface_positions, surface_triangles, unmeasured);
  report.surface_points_left_out = samples.left_out;
  if (samples.vertices.rows() == 0) {
    throw ricci::InvalidInputError("surface: every triangle left out");
  }
  const KnownSampleDistances* known = options.known_samples;
  const SampleHits hits =
      surface_to_scan(samples, scan, options.threads, known ? &known->tables() : nullptr);
  Eigen::VectorXd back(samples.vertices.rows() + samples.centroids.rows());
  back.head(samples.vertices.rows()) = distances_of(hits.vertices);
  back.tail(samples.centroids.rows()) = hits.centroids;
  report.surface_points = static_cast<int>(back.size());
  report.surface_to_scan_max = back.maxCoeff(&farthest);
  report.surface_to_scan_max_point =
      farthest < samples.vertices.rows()
          ? samples.vertices.row(farthest).transpose()
          : samples.centroids.row(farthest - samples.vertices.rows()).transpose();
  std::vector<double> sorted(back.data(), back.data() + back.size());
  const auto k = static_cast<std::size_t>(0.99 * static_cast<double>(sorted.size() - 1));
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(k), sorted.end());
  report.surface_to_scan_p99 = sorted[k];

  // Coverage: four samples per scan triangle, area-weighted.
  Eigen::MatrixX3d cover(static_cast<Eigen::Index>(4 * scan_triangles.size()), 3);
  Eigen::VectorXd area(static_cast<Eigen::Index>(scan_triangles.size()));
  for (std::size_t t = 0; t < scan_triangles.size(); ++t) {
    const auto& tri = scan_triangles[t];
    const Eigen::RowVector3d a = scan_positions.row(tri[0]), b = scan_positions.row(tri[1]),
                             c = scan_positions.row(tri[2]);
    area[static_cast<Eigen::Index>(t)] = 0.5 * (b - a).cross(c - a).norm();
    const auto row = static_cast<Eigen::Index>(4 * t);
    cover.row(row) = (a + b + c) / 3.0;
    cover.row(row + 1) = (4.0 * a + b + c) / 6.0;
    cover.row(row + 2) = (a + 4.0 * b + c) / 6.0;
    cover.row(row + 3) = (a + b + 4.0 * c) / 6.0;
  }
  // A sample is covered when a corner's nearest surface point lies within the tolerance (its
  // own nearest point is no farther); the others are measured, searched from the corner's hit.
  const auto corner = [&](std::size_t i, int k) -> const ricci::SoupHit& {
    return fit_hits[static_cast<std::size_t>(scan_triangles[i / 4][static_cast<std::size_t>(k)])];
  };
  std::vector<char> inside(static_cast<std::size_t>(cover.rows()), 0);
  std::vector<std::size_t> measured;
  std::vector<Eigen::Vector3d> uncertain;
  for (std::size_t i = 0; i < inside.size(); ++i) {
    const Eigen::Vector3d sample = cover.row(static_cast<Eigen::Index>(i)).transpose();
    for (int k = 0; k < 3 && !inside[i]; ++k)
      inside[i] = (corner(i, k).point - sample).norm() <= report.coverage_tolerance;
    if (inside[i]) continue;
    measured.push_back(i);
    uncertain.push_back(sample);
  }
  const std::vector<ricci::SoupHit> cover_hits =
      closest_hits(surface, to_rows(uncertain), options.threads, [&](std::size_t j) {
        const std::size_t i = measured[j];
        return &corner(i, i % 4 == 0 ? 0 : static_cast<int>(i % 4) - 1);
      });
  for (std::size_t j = 0; j < measured.size(); ++j)
    inside[measured[j]] = cover_hits[j].distance <= report.coverage_tolerance;
  double covered = 0.0;
  for (Eigen::Index t = 0; t < area.size(); ++t) {
    int count = 0;
    for (int s = 0; s < 4; ++s) count += inside[static_cast<std::size_t>(4 * t + s)];
    covered += area[t] * count / 4.0;
  }
  report.coverage = area.sum() > 0.0 ? std::min(1.0, covered / area.sum()) : 1.0;

  // Boundaries.
  const auto surface_rim = soup_boundary_edges(surface_triangles);
  auto scan_rim = soup_boundary_edges(scan_triangles);
  if (!unmeasured_rim.empty()) {
    const auto left_out = [&unmeasured_rim](const std::array<int, 2>& e) {
      return unmeasured_rim[static_cast<std::size_t>(e[0])] &&
             unmeasured_rim[static_cast<std::size_t>(e[1])];
    };
    const auto kept = std::remove_if(scan_rim.begin(), scan_rim.end(), left_out);
    report.scan_boundary_edges_left_out = static_cast<int>(scan_rim.end() - kept);
    scan_rim.erase(kept, scan_rim.end());
  }
  report.surface_boundary_edges = static_cast<int>(surface_rim.size());
  report.scan_boundary_edges = static_cast<int>(scan_rim.size());
  if (!surface_rim.empty() && !scan_rim.empty()) {
    const ricci::SegmentSoupDistance surface_curve(surface_positions, surface_rim);
    const ricci::SegmentSoupDistance scan_curve(scan_positions, scan_rim);
    const Eigen::MatrixX3d surface_side = edge_samples(surface_positions, surface_rim);
    const Eigen::MatrixX3d scan_side = edge_samples(scan_positions, scan_rim);
    const Eigen::VectorXd out = parallel_distances(scan_curve, surface_side, options.threads);
    const Eigen::VectorXd in = parallel_distances(surface_curve, scan_side, options.threads);
    Eigen::Index worst_out = 0, worst_in = 0;
    report.surface_boundary_to_scan_boundary = out.maxCoeff(&worst_out);
    report.scan_boundary_to_surface_boundary = in.maxCoeff(&worst_in);
    const bool outward =
        report.surface_boundary_to_scan_boundary >= report.scan_boundary_to_surface_boundary;
    report.boundary_hausdorff = outward ? report.surface_boundary_to_scan_boundary
                                        : report.scan_boundary_to_surface_boundary;
    report.boundary_hausdorff_point =
        outward ? surface_side.row(worst_out).transpose() : scan_side.row(worst_in).transpose();
  }
  return report;
}

}  // namespace

PreparedScan::PreparedScan(Eigen::MatrixX3d positions, std::vector<std::array<int, 3>> triangles)
    : positions_(std::move(positions)), triangles_(std::move(triangles)) {
  check_indices(positions_, triangles_, "scan");
  tree_ = std::make_unique<ricci::TriangleSoupDistance>(positions_, triangles_);
}

PreparedScan::~PreparedScan() = default;

KnownSampleDistances::KnownSampleDistances(const Eigen::MatrixX3d& positions,
                                           const std::vector<std::array<int, 3>>& triangles,
                                           const PreparedScan& scan, int threads,
                                           const std::function<bool()>& stop)
    : scan_(&scan), tables_(std::make_unique<Tables>()) {
  check_indices(positions, triangles, "surface");
  const SurfaceSamples samples = surface_samples(positions, triangles, {});
  const SampleHits hits = surface_to_scan(samples, scan.tree(), threads, nullptr, stop);
  tables_->vertices.reserve(hits.vertices_done);
  for (std::size_t i = 0; i < hits.vertices_done; ++i)
    tables_->vertices.emplace(Tables::vertex_key(samples.vertices, static_cast<Eigen::Index>(i)),
                              hits.vertices[i]);
  tables_->centroids.reserve(static_cast<std::size_t>(hits.centroids.size()));
  for (Eigen::Index i = 0; i < hits.centroids.size(); ++i)
    if (hits.centroid_done[static_cast<std::size_t>(i)])
      tables_->centroids.emplace(
        Tables::centroid_key(samples.centroids, i, samples.vertices,
                             samples.centroid_corner[static_cast<std::size_t>(i)]),
        hits.centroids[i]);
}

KnownSampleDistances::~KnownSampleDistances() = default;
KnownSampleDistances::KnownSampleDistances(KnownSampleDistances&&) noexcept = default;
KnownSampleDistances& KnownSampleDistances::operator=(KnownSampleDistances&&) noexcept = default;

std::size_t KnownSampleDistances::vertex_count() const { return tables_->vertices.size(); }
std::size_t KnownSampleDistances::centroid_count() const { return tables_->centroids.size(); }

ScanDistanceReport measure_against_scan(const Eigen::MatrixX3d& surface_positions,
                                        const std::vector<std::array<int, 3>>& surface_triangles,
                                        const Eigen::MatrixX3d& scan_positions,
                                        const std::vector<std::array<int, 3>>& scan_triangles,
                                        const ScanDistanceOptions& options) {
  check_surface(surface_positions, surface_triangles, options);
  check_indices(scan_positions, scan_triangles, "scan");
  if (options.known_samples)
    throw ricci::InvalidInputError("known_samples need the prepared scan they were measured on");
  // The two search trees are independent: built at once, one per thread.
  std::optional<ricci::TriangleSoupDistance> trees[2];
  run_workers(options.threads == 1 ? 1 : 2, [&](int k) {
    if (k == 0 || options.threads == 1) trees[0].emplace(surface_positions, surface_triangles);
    if (k == 1 || options.threads == 1) trees[1].emplace(scan_positions, scan_triangles);
  });
  return measure_with_trees(surface_positions, surface_triangles, *trees[0], scan_positions,
                            scan_triangles, *trees[1], options);
}

ScanDistanceReport measure_against_scan(const Eigen::MatrixX3d& surface_positions,
                                        const std::vector<std::array<int, 3>>& surface_triangles,
                                        const PreparedScan& scan, const ScanDistanceOptions& options) {
  check_surface(surface_positions, surface_triangles, options);
  if (options.known_samples && &options.known_samples->scan() != &scan)
    throw ricci::InvalidInputError("known_samples were measured on another prepared scan");
  const ricci::TriangleSoupDistance surface(surface_positions, surface_triangles);
  return measure_with_trees(surface_positions, surface_triangles, surface, scan.positions(),
                            scan.triangles(), scan.tree(), options);
}

}  // namespace spline
