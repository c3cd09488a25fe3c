#pragma once
// The manifold DMS spline space over ricci's affine atlas (manifold-splines paper section 5):
// F(u) = sum_I sum_beta c_{I,beta} N_{I,beta}(tau_I(u)).
//
// Knots. Every domain vertex v has ONE home cloud, made by make_knot_cloud (knot_cloud.h: the rule
// and its reasons) in a home chart where v's whole domain one-ring is one planar piece: the
// neighbourhood chart of the lowest-numbered domain face around v. In any other chart (or another
// copy of v in the same chart) the cloud is the home cloud moved by the rigid motion relating the
// two placements of a face around v (the atlas transition, or the face's own corners when the
// atlas has none for that pair). Blossoms and DMS basis functions are affine invariant, so every
// chart that holds a point's neighbourhood sees the same basis functions there.
//
// Functions. Domain face I (atlas.in_domain[I] != 0, a neighbourhood chart, counter-clockwise and
// not vanishingly small there; the rare others are left out like the hole, see excluded_faces())
// carries (n + 1)(n + 2)/2 functions, beta in multi_indices(n) order relative to I's corners (corner k =
// to_vertex of the k-th halfedge of face_halfedges(mesh, I), the atlas' corner order): global index
// domain_index(I) * functions_per_face() + beta. Faces of the cone's one-ring carry none.
//
// Evaluation. A point is a face and barycentric coordinates (in the same corner order). It is
// evaluated in a chart holding the face's vertex-neighbourhood as one glued piece (by default the
// atlas' neighbourhood chart); per chart a PlanarDmsSpace is built on first use and cached
// (thread-safe), over the domain faces it places as their neighbourhood charts do (not the
// central chart's faces next to a large cone, broken by its rounding). Only functions of faces
// sharing a chart vertex with the point's face can reach it (clouds stay inside their vertex
// stars), so those are kept: this also makes self-overlapping charts (the central chart around a
// cone of angle 6 pi) harmless.
#include <Eigen/Core>
#include <Eigen/LU>
#include <array>
#include <memory>
#include <mutex>
#include <vector>

#include "ricci/atlas/atlas.h"
#include "ricci/mesh/mesh.h"
#include "spline/basis/blossom.h"
#include "spline/basis/planar_space.h"
#include "spline/knots/knot_cloud.h"

namespace spline {

struct ManifoldSplineOptions {
  int degree = 3;          ///< n, in 1..kMaxDmsDegree
  KnotCloudOptions knots;  ///< the home-cloud rule
};

/// One basis function at a point: global function index and its jet in the chart's frame.
struct ManifoldBasisSample {
  int function = 0;
  Jet jet;
};

/// A point of the domain: a face and barycentric coordinates in the face's corner order.
struct DomainPoint {
  int face = -1;
  Eigen::Vector3d barycentric = Eigen::Vector3d::Constant(1.0 / 3.0);
};

class ManifoldSplineSpace {
 public:
  /// \pre `atlas` was built on `mesh` (e.g. build_one_cone_atlas(...).problem.mesh and .atlas).
  /// \throw ricci::InvalidInputError on a degree out of range or an atlas of another mesh;
  ///        ricci::TopologyError when a domain vertex has no chart holding its one-ring.
  ManifoldSplineSpace(const ricci::Mesh& mesh, const ricci::AffineAtlas& atlas,
                      const ManifoldSplineOptions& options = {});
  /// The same space with given home clouds (by vertex, as home_cloud() returns them: empty for
  /// vertices outside the domain) instead of make_knot_cloud's: for a space read back from a
  /// file, so that it does not depend on the platform's sin / cos. Each cloud must start at its
  /// vertex's home-chart position (exactly) and keep its knots closer to it than half the
  /// smallest inradius of the vertex's domain triangles there (which guarantees the DMS
  /// conditions, knot_cloud.h).
  /// \throw as above, and ricci::InvalidInputError naming the first vertex whose cloud breaks
  ///        that (or a cloud count other than the vertex count, a degree other than `degree`).
  ManifoldSplineSpace(const ricci::Mesh& mesh, const ricci::AffineAtlas& atlas, int degree,
                      std::vector<KnotCloud> home_clouds);
  ~ManifoldSplineSpace();
  ManifoldSplineSpace(const ManifoldSplineSpace&) = delete;
  ManifoldSplineSpace& operator=(const ManifoldSplineSpace&) = delete;

  [[nodiscard]] int degree() const { return degree_; }
  [[nodiscard]] int functions_per_face() const { return multi_index_count(degree_); }
  [[nodiscard]] int face_count() const { return static_cast<int>(domain_index_.size()); }
  [[nodiscard]] int domain_face_count() const { return static_cast<int>(domain_faces_.size()); }
  [[nodiscard]] int function_count() const { return domain_face_count() * functions_per_face(); }
  [[nodiscard]] bool in_domain(int face) const { return domain_index_[face] >= 0; }
  /// Position of `face` among the domain faces, -1 outside the domain.
  [[nodiscard]] int domain_index(int face) const { return domain_index_[face]; }
  [[nodiscard]] const std::vector<int>& domain_faces() const { return domain_faces_; }
  [[nodiscard]] int function_index(int face, int beta) const {
    return domain_index_[face] * functions_per_face() + beta;
  }
  /// The face across the edge opposite corner k of `face` (-1 on a boundary).
  [[nodiscard]] int neighbour(int face, int k) const { return neighbours_[face][k]; }
  [[nodiscard]] const ricci::AffineAtlas& atlas() const { return atlas_; }
  [[nodiscard]] const KnotCloud& home_cloud(int vertex) const { return home_clouds_[vertex]; }
  [[nodiscard]] int home_chart(int vertex) const { return home_chart_[vertex]; }
  /// Atlas domain faces left out: no neighbourhood chart, flipped or degenerate in it, or on a
  /// surface of genus >= 4, an inradius there below 1e-13 of its chart coordinates; and on such
  /// a surface, below genus 8 or where the faces so left out form disks, also those flipped or
  /// that small in any chart or below 1e-8 of the median face's inradius.
  [[nodiscard]] int excluded_faces() const { return excluded_faces_; }

  /// True when `chart` holds every domain face sharing a vertex with `face` glued around it.
  [[nodiscard]] bool holds_neighbourhood(int chart, int face) const;
  /// The chart used by default for points of `face`: the atlas' neighbourhood chart.
  [[nodiscard]] int chart_of(int face) const { return atlas_.neighbourhood_chart[face]; }
  /// The point of `face` with these barycentric coordinates in `chart`'s coordinates.
  [[nodiscard]] Eigen::Vector2d chart_point(int chart, int face, const Eigen::Vector3d& bary) const;
  /// The clouds of `face`'s three corners as seen in `chart` (corner order).
  /// \throw ricci::InvalidInputError when the chart does not hold the face or it is not a domain
  /// face.
  [[nodiscard]] std::array<KnotCloud, 3> face_clouds(int chart, int face) const;

  /// All functions non-zero at the point (value or derivatives), jets in `chart`'s frame
  /// (chart -1: chart_of(face)). `tie` picks the side of knot lines (one-sided derivatives).
  /// BasisDerivatives::none: the functions with a non-zero value, values only (cheaper; the
  /// values are the same numbers).
  /// \throw ricci::InvalidInputError for a face outside the domain or a chart not holding it.
  [[nodiscard]] std::vector<ManifoldBasisSample> evaluate_basis(
      const DomainPoint& point, int chart = -1, const TieBreak& tie = {},
      BasisDerivatives derivatives = BasisDerivatives::second) const;
  /// Same at a point u given in `chart`'s coordinates near `face` (u may leave the face slightly:
  /// any point of the face's neighbourhood is evaluated correctly).
  [[nodiscard]] std::vector<ManifoldBasisSample> evaluate_basis_at(
      int chart, int face, const Eigen::Vector2d& u, const TieBreak& tie = {},
      BasisDerivatives derivatives = BasisDerivatives::second) const;
  /// The same into `out` (replacing its contents): no allocation once `out` has grown.
  void evaluate_basis_at(int chart, int face, const Eigen::Vector2d& u, const TieBreak& tie,
                         BasisDerivatives derivatives, std::vector<ManifoldBasisSample>& out) const;

  /// Domain faces whose functions can be non-zero on `face` (evaluated in chart_of(face)): the
  /// faces sharing a chart vertex with it there, itself included; ascending. Every sample of
  /// evaluate_basis on `face` (default chart) belongs to one of them.
  [[nodiscard]] std::vector<int> reaching_faces(int face) const;

  /// Control points (function_count() x k) reproducing p (given in `chart`'s coordinates) on
  /// every domain face `chart` holds; rows of other faces are zero.
  [[nodiscard]] Eigen::MatrixXd control_points_of(const BivariatePolynomial& p, int chart) const;

  /// The cached planar space of `chart` and the original face of each of its triangles.
  struct ChartSpace;
  [[nodiscard]] const ChartSpace& chart_space(int chart) const;

 private:
  void build_domain(const ricci::Mesh& mesh);
  // Makes the home clouds by `options`, or checks and installs `given` when it is not null.
  void build_home_clouds(const ricci::Mesh& mesh, const ManifoldSplineOptions& options,
                         std::vector<KnotCloud>* given);
  [[nodiscard]] KnotCloud cloud_in_chart(int chart, int face, int corner) const;
  // Whether `chart` places domain `face` as its neighbourhood chart does (same edge lengths,
  // counter-clockwise); charts that do not (rounding next to a large cone) leave it out.
  [[nodiscard]] bool same_shape_as_home(int chart, int face) const;
  [[nodiscard]] std::unique_ptr<ChartSpace> build_chart_space(int chart) const;
  // Whether `chart` is the neighbourhood chart of domain `face` (home_corners_, home_row_).
  [[nodiscard]] bool is_home(int chart, int face) const;

  int degree_ = 0;
  int excluded_faces_ = 0;
  ricci::AffineAtlas atlas_;
  std::vector<int> domain_index_;               // by face
  std::vector<int> domain_faces_;               // domain faces, ascending
  std::vector<std::array<int, 3>> neighbours_;  // by face, across the edge opposite corner k
  std::vector<std::vector<int>> vertex_faces_;  // by vertex: incident domain faces
  std::vector<KnotCloud> home_clouds_;          // by vertex (empty outside the domain)
  std::vector<int> home_chart_, home_face_;     // by vertex
  // By face, for domain faces: corners and row in chart_of(face) (row -1 elsewhere).
  std::vector<Eigen::Matrix<double, 3, 2>> home_corners_;
  std::vector<int> home_row_;
  mutable std::vector<std::unique_ptr<ChartSpace>> chart_spaces_;
  mutable std::unique_ptr<std::once_flag[]> chart_once_;
};

/// The planar space of one chart: its domain faces as triangles over its used chart vertices.
struct ManifoldSplineSpace::ChartSpace {
  std::unique_ptr<PlanarDmsSpace> space;  ///< null when the chart holds no domain face
  std::vector<int> face_of_triangle;  ///< original face by local triangle
  std::vector<int> triangle_of_row;   ///< by row of Chart::faces: local triangle or -1
  std::vector<std::vector<int>> triangles_at_vertex;  ///< by local vertex: its triangles
  /// By local triangle t: the triangles sharing a vertex with t (t included), ascending, in
  /// around[around_start[t] .. around_start[t + 1]): the only ones whose functions can reach t.
  std::vector<int> around_start, around;
};

/// Position, derivatives (in the evaluating chart's frame) and unit normal of the surface.
struct SurfaceJet {
  int chart = -1;  ///< the frame of the derivatives
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d du = Eigen::Vector3d::Zero(), dv = Eigen::Vector3d::Zero();
  Eigen::Vector3d duu = Eigen::Vector3d::Zero(), duv = Eigen::Vector3d::Zero(),
                  dvv = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  ///< du x dv normalised (zero if degenerate)
};

/// A manifold spline surface: a space and one 3D control point per function.
struct ManifoldSpline {
  std::shared_ptr<const ManifoldSplineSpace> space;
  Eigen::MatrixX3d control_points;  ///< space->function_count() rows

  /// The surface at `point` up to `derivatives`: none gives the position alone, first also du,
  /// dv and the normal, second also duu, duv, dvv (fields not computed stay zero; those computed
  /// have the same bits at every order).
  /// \throw ricci::InvalidInputError as evaluate_basis, or on a wrong control-point count.
  [[nodiscard]] SurfaceJet evaluate(const DomainPoint& point, int chart = -1,
                                    const TieBreak& tie = {},
                                    BasisDerivatives derivatives = BasisDerivatives::second) const;
  [[nodiscard]] SurfaceJet evaluate_at(
      int chart, int face, const Eigen::Vector2d& u, const TieBreak& tie = {},
      BasisDerivatives derivatives = BasisDerivatives::second) const;
};

/// Whether the samples' values sum to 1 within `tolerance`: false next to the domain's rim, where
/// the functions of the faces beyond it are missing.
[[nodiscard]] bool is_partition_of_unity(const std::vector<ManifoldBasisSample>& samples,
                                         double tolerance = 1e-9);

/// Barycentric coordinates of the chart point u in the chart triangle p (rows: its corners).
/// \pre p is not degenerate.
[[nodiscard]] inline Eigen::Vector3d barycentric_in(const Eigen::Matrix<double, 3, 2>& p,
                                                    const Eigen::Vector2d& u) {
  Eigen::Matrix2d m;
  m.col(0) = (p.row(1) - p.row(0)).transpose();
  m.col(1) = (p.row(2) - p.row(0)).transpose();
  const Eigen::Vector2d l = m.partialPivLu().solve(u - p.row(0).transpose());
  return {1.0 - l.x() - l.y(), l.x(), l.y()};
}

/// Combines basis samples with control points (rows indexed by function) into a surface jet,
/// up to `derivatives` (as ManifoldSpline::evaluate).
[[nodiscard]] SurfaceJet combine(const std::vector<ManifoldBasisSample>& samples,
                                 const Eigen::MatrixX3d& control_points, int chart,
                                 BasisDerivatives derivatives = BasisDerivatives::second);

}  // namespace spline
