#include "ricci/hyperbolic/layout_h2.h"

#include <cmath>
#include <deque>
#include <string>
#include <vector>

#include "ricci/hyperbolic/polish_h2.h"
#include "ricci/layout/layout_e2.h"
#include "ricci/mesh/errors.h"

namespace ricci {
namespace {

/// Corner angle at from_vertex(h) of h's face, from the face's hyperbolic lengths, in quad
/// precision by the half-angle formula (hyperbolic_angles_q), which loses no digits for thin or
/// small triangles.
RealQ angle_at_from(const Mesh& mesh, const LengthsQ& lengths, HalfedgeHandle h) {
  const HalfedgeHandle h1 = mesh.next_halfedge_handle(h), h2 = mesh.next_halfedge_handle(h1);
  const auto length = [&](HalfedgeHandle g) {
    return lengths[static_cast<size_t>(mesh.edge_handle(g).idx())];
  };
  // Triangle with vertices 0 = from(h), 1 = to(h), 2 = to(h1); l[k] opposite vertex k.
  const RealQ l[3] = {length(h1), length(h2), length(h)};
  RealQ theta[3];
  if (!hyperbolic_angles_q(l, theta)) {
    throw InvalidInputError("layout_h2: face " + std::to_string(mesh.face_handle(h).idx()) +
                            " violates the hyperbolic triangle inequality");
  }
  return theta[0];
}

/// A face in its own frame: from(h) at 0, to(h) on the positive real axis, the third vertex
/// above; z[k] is the position of the from-vertex of the k-th halfedge h, next(h), prev(h).
/// Built in quad precision: a frame's rounding at the centre is carried to distance d as
/// eps e^d, so long double corners left local defects of 1e-12 at the far end of a genus-10
/// domain.
struct CanonicalFace {
  HalfedgeHandle h[3];
  ComplexQ z[3];
};

CanonicalFace canonical_face(const Mesh& mesh, const LengthsQ& lengths, HalfedgeHandle h) {
  CanonicalFace c;
  c.h[0] = h;
  c.h[1] = mesh.next_halfedge_handle(h);
  c.h[2] = mesh.next_halfedge_handle(c.h[1]);
  const auto half_length = [&](HalfedgeHandle g) {
    return lengths[static_cast<size_t>(mesh.edge_handle(g).idx())] / 2;
  };
  c.z[0] = ComplexQ();
  c.z[1] = ComplexQ(tanh_q(half_length(h)), 0);
  const RealQ r = tanh_q(half_length(c.h[2]));
  const RealQ angle = angle_at_from(mesh, lengths, h);
  c.z[2] = ComplexQ(r * cos_q(angle), r * sin_q(angle));
  return c;
}

}  // namespace

Complex hyperbolic_centre(const Eigen::VectorXcd& points, int iterations) {
  Complex c = 0.0;
  for (int k = 1; k <= iterations; ++k) {
    const Mobius to_c = Mobius::from_rotation_point(0.0, c);
    Complex far = 0.0;
    for (Eigen::Index i = 0; i < points.size(); ++i) {
      const Complex z = to_c(points[i]);
      if (std::abs(z) > std::abs(far)) far = z;
    }
    if (std::abs(far) == 0.0) break;
    const double d = 2.0 * std::atanh(std::abs(far));
    c = to_c.inverse()(std::polar(disk_radius(d / (k + 1)), std::arg(far)));
  }
  return c;
}

LayoutH2Result layout_h2(const Mesh& mesh, const Eigen::VectorXd& edge_lengths,
                         const LayoutH2Options& options) {
  return layout_h2(mesh, LengthsQ(edge_lengths.begin(), edge_lengths.end()), options);
}

LayoutH2Result layout_h2(const Mesh& mesh, const LengthsL& edge_lengths,
                         const LayoutH2Options& options) {
  return layout_h2(mesh, LengthsQ(edge_lengths.begin(), edge_lengths.end()), options);
}

LayoutH2Result layout_h2(const Mesh& mesh, const LengthsQ& edge_lengths,
                         const LayoutH2Options& options) {
  if (options.seed_face < 0 && options.recentre) {
    LayoutH2Options first = options;
    first.recentre = false;
    const LayoutH2Result draft = layout_h2(mesh, edge_lengths, first);
    const Complex c = hyperbolic_centre(draft.positions);
    int nearest = 0;
    for (Eigen::Index i = 0; i < draft.positions.size(); ++i) {
      if (disk_distance(draft.positions[i], c) < disk_distance(draft.positions[nearest], c)) {
        nearest = static_cast<int>(i);
      }
    }
    for (auto h : mesh.voh_range(VertexHandle(nearest))) {
      if (!mesh.is_boundary(h)) {
        first.seed_face = mesh.face_handle(h).idx();
        break;
      }
    }
    return layout_h2(mesh, edge_lengths, first);
  }
  if (edge_lengths.size() != mesh.n_edges()) {
    throw InvalidInputError("layout_h2: " + std::to_string(edge_lengths.size()) + " lengths for " +
                            std::to_string(mesh.n_edges()) + " edges");
  }
  LayoutH2Result result;
  result.seed_face = options.seed_face >= 0 ? options.seed_face : central_face_of(mesh);
  if (result.seed_face >= static_cast<int>(mesh.n_faces())) {
    throw InvalidInputError("layout_h2: seed face " + std::to_string(result.seed_face) +
                            " out of range");
  }
  result.positions = Eigen::VectorXcd::Constant(mesh.n_vertices(), Complex(NAN, NAN));
  std::vector<char> placed(mesh.n_vertices(), 0), reached(mesh.n_faces(), 0);
  // Faces are developed by composing frames: a face's frame maps its canonical placement (see
  // CanonicalFace) into the disk, and a neighbour's frame is this frame times the Möbius map
  // between the two canonical placements, computed from the lengths alone near the centre. Unlike
  // placing each vertex from its two already-placed neighbours (whose rounding is amplified by
  // the ratio of the triangle's sides at every step, a product that grows along a long front),
  // the frames only accumulate one rounding per step.
  // The frames are composed in quad precision: a frame reaching distance d has entries ~e^{d/2}
  // and keeps its image exact only to eps e^d (mobius_q.h).
  struct Item {
    HalfedgeHandle h;
    MobiusQ frame;
  };
  const FaceHandle seed(result.seed_face);
  result.precise_positions.assign(mesh.n_vertices(), ComplexL(NAN, NAN));
  result.quad_positions.assign(mesh.n_vertices(), ComplexQ());
  std::deque<Item> queue{{mesh.halfedge_handle(seed), MobiusQ()}};
  reached[seed.idx()] = 1;
  int reached_count = 1;
  while (!queue.empty()) {
    const Item item = queue.front();
    queue.pop_front();
    const CanonicalFace c = canonical_face(mesh, edge_lengths, item.h);
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.from_vertex_handle(c.h[k]).idx();
      if (!placed[v]) {
        const ComplexQ z = item.frame(c.z[k]);
        result.quad_positions[static_cast<size_t>(v)] = z;
        result.precise_positions[static_cast<size_t>(v)] = z.to_long();
        result.positions[v] = Complex(z.to_long());
        placed[v] = 1;
      }
    }
    for (int k = 0; k < 3; ++k) {
      const HalfedgeHandle o = mesh.opposite_halfedge_handle(c.h[k]);
      if (mesh.is_boundary(o) || reached[mesh.face_handle(o).idx()]) continue;
      reached[mesh.face_handle(o).idx()] = 1;
      ++reached_count;
      // In the neighbour's frame for o, from(o) = to(h_k) is at 0 and to(o) = from(h_k) on the
      // positive axis: the map from that frame into ours is the inverse of disk_to_centre.
      const MobiusQ into_ours = disk_to_centre_q(c.z[(k + 1) % 3], c.z[k]).inverse();
      queue.push_back({o, (item.frame * into_ours).normalised()});
    }
  }
  if (reached_count != static_cast<int>(mesh.n_faces())) {
    throw TopologyError("layout_h2: " + std::to_string(mesh.n_faces() - reached_count) +
                        " faces cannot be reached from seed face " +
                        std::to_string(result.seed_face) + " (mesh not connected)");
  }
  Eigen::VectorXd rounded(static_cast<Eigen::Index>(edge_lengths.size()));
  for (size_t e = 0; e < edge_lengths.size(); ++e) {
    rounded[static_cast<Eigen::Index>(e)] = static_cast<double>(edge_lengths[e]);
  }
  measure_layout_h2(mesh, rounded, result.positions, result);
  return result;
}

void measure_layout_h2(const Mesh& mesh, const Eigen::VectorXd& edge_lengths,
                       const Eigen::VectorXcd& positions, LayoutH2Result& result) {
  result.min_signed_area = INFINITY;
  result.flipped_faces = 0;
  for (auto f : mesh.faces()) {
    Complex z[3];
    int k = 0;
    for (auto v : mesh.fv_range(f)) z[k++] = positions[v.idx()];
    const double area = 0.5 * std::imag(std::conj(z[1] - z[0]) * (z[2] - z[0]));
    result.min_signed_area = std::min(result.min_signed_area, area);
    if (!(area > 0)) ++result.flipped_faces;
  }
  result.max_relative_length_error = 0.0;
  for (auto e : mesh.edges()) {
    const auto h = mesh.halfedge_handle(e, 0);
    const double d = disk_distance(positions[mesh.from_vertex_handle(h).idx()],
                                   positions[mesh.to_vertex_handle(h).idx()]);
    result.max_relative_length_error =
        std::max(result.max_relative_length_error,
                 std::abs(d - edge_lengths[e.idx()]) / edge_lengths[e.idx()]);
  }
  result.max_radius = positions.cwiseAbs().maxCoeff();
}

}  // namespace ricci
