#pragma once
// Where the input's points lie on a flipped intrinsic triangulation, and back. The conformal flow
// (conformal_flow.h) changes the triangulation by Ptolemy flips, which keep the decorated ideal
// hyperbolic surface of the Penner coordinates, not a Euclidean one (a Ptolemy diagonal is the
// Euclidean one only on a cyclic quad). So points are tracked on that hyperbolic surface, as
// Gillespie, Springborn and Crane (2021, section 5) define the correspondence: a Euclidean
// triangle with lengths l_ij is the Klein model of its ideal triangle in its circumcircle, and a
// point's barycentric coordinates are its coefficients against the decoration's light-like
// vectors p_i (-2 <p_i, p_j> = l_ij^2 in Minkowski space R^{2,1}). A flip lays the quad's four
// vectors out in one space, p_l = alpha p_i + beta p_j + gamma p_k with alpha = l_jl l_kl /
// (l_ij l_ik), beta = l_il l_kl / (l_ij l_jk), gamma = -l_il l_jl / (l_ik l_jk), and re-expresses
// each point of the quad in the new triangle holding it: exact up to rounding, O(1) per point
// moved, independent of u (vertex scaling rescales the p_i). Signposts (Sharp, Soliman, Crane
// 2019) track Euclidean flips, whose diagonal is not the Ptolemy one; integer coordinates track
// edges, not points, and place points only through a common subdivision.
//
//   ricci::IntrinsicTriangulation initial = ricci::make_intrinsic_triangulation(mesh, lengths);
//   ricci::IntrinsicFlowResult r = ricci::intrinsic_conformal_flow(initial, target);
//   ricci::IntrinsicCorrespondence map(initial, r.flip_log);
//   std::vector<ricci::TriangulationPoint> on_final = map.to_final(input_points);
#include <vector>

#include <Eigen/Core>

#include "ricci/intrinsic/intrinsic_triangulation.h"

namespace ricci {

/// A point of an intrinsic triangulation: a face and weights at its three corners (corner k is
/// the tail of halfedge 3 face + k), >= 0 and summing to 1. They are the point's barycentric
/// coordinates in the Euclidean triangle of the lengths at u = 0 (the log_length), which for
/// make_intrinsic_triangulation's faces are the input mesh's triangles; barycentric_at gives
/// them at other scale factors.
struct TriangulationPoint {
  int face = -1;
  Eigen::Vector3d weights = Eigen::Vector3d::Zero();
};

/// Barycentric coordinates of `point` in its face's Euclidean triangle at scale factors u:
/// b_k proportional to weights_k exp(-u at corner k).
/// \throw InvalidInputError for a face out of range or u of the wrong size.
[[nodiscard]] Eigen::Vector3d barycentric_at(const IntrinsicTriangulation& tri,
                                             const TriangulationPoint& point,
                                             const Eigen::VectorXd& u);

/// The point of `face` whose barycentric coordinates at scale factors u are `barycentric`
/// (>= 0, not all 0); the inverse of barycentric_at. \throw InvalidInputError as above, or for
/// negative or all-zero coordinates.
[[nodiscard]] TriangulationPoint point_at_barycentric(const IntrinsicTriangulation& tri, int face,
                                                      const Eigen::Vector3d& barycentric,
                                                      const Eigen::VectorXd& u);

/// The point at vertex v: weight 1 at a corner of v (a search of the corners: vertex_points for
/// all of them). \throw InvalidInputError for v out of range or without a face.
[[nodiscard]] TriangulationPoint vertex_point(const IntrinsicTriangulation& tri, int v);

/// vertex_point of every vertex, by vertex index, in one pass over the corners.
/// \throw InvalidInputError for a vertex without a face.
[[nodiscard]] std::vector<TriangulationPoint> vertex_points(const IntrinsicTriangulation& tri);

/// The point's 3D position when tri's faces are flat triangles between `positions` (#V by 3),
/// as make_intrinsic_triangulation's faces are the input mesh's: sum_k weights_k x(corner k).
/// \throw InvalidInputError for a face out of range or positions of the wrong size.
[[nodiscard]] Eigen::Vector3d point_position(const IntrinsicTriangulation& tri,
                                             const Eigen::MatrixX3d& positions,
                                             const TriangulationPoint& point);

/// The correspondence between an initial intrinsic triangulation and the one a sequence of
/// flips made of it (IntrinsicFlowResult::flip_log): the flips are replayed once, each keeping
/// its quad's layout (above), and points are carried through them in either direction.
class IntrinsicCorrespondence {
 public:
  /// Replays `flip_log` (edge indices, flipped in order by flip_edge) on `initial`.
  /// \throw InvalidInputError for an edge out of range or not flippable when its turn comes.
  IntrinsicCorrespondence(IntrinsicTriangulation initial, const std::vector<int>& flip_log);

  [[nodiscard]] const IntrinsicTriangulation& initial() const { return initial_; }
  /// The triangulation after every flip: equal to the flow's result.triangulation.
  [[nodiscard]] const IntrinsicTriangulation& final_triangulation() const { return final_; }
  [[nodiscard]] int flips() const { return static_cast<int>(flips_.size()); }

  /// Where points of the initial triangulation lie on the final one.
  /// \throw InvalidInputError for a face out of range or weights that are negative or all 0.
  [[nodiscard]] std::vector<TriangulationPoint> to_final(
      std::vector<TriangulationPoint> points) const;
  /// Where points of the final triangulation lie on the initial one. \throw as to_final.
  [[nodiscard]] std::vector<TriangulationPoint> to_initial(
      std::vector<TriangulationPoint> points) const;

  /// One flip: the slots of the flipped edge's halfedge and twin before the flip (face A =
  /// (i, j, k) from slot h, face B = (j, i, l) from slot t; after it A = (l, k, i) and
  /// B = (k, l, j) in the same slots) and p_l = alpha p_i + beta p_j + gamma p_k.
  struct Flip {
    int h = 0, t = 0;
    double alpha = 0, beta = 0, gamma = 0;
  };

 private:
  IntrinsicTriangulation initial_, final_;
  std::vector<Flip> flips_;
};

}  // namespace ricci
