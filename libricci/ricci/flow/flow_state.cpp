#include "ricci/flow/flow_state.h"

#include "ricci/metric/circle_packing.h"

namespace ricci {

bool evaluate_flow_state(const MeshTables& t, Geometry g, const Eigen::VectorXd& eta,
                         const Eigen::VectorXd& u, FlowState& s) {
  const int nv = t.num_vertices(), ne = t.num_edges(), nf = t.num_faces();
  s.bad_vertex = s.bad_edge = s.bad_face = -1;
  s.u = u;
  s.gamma.resize(nv);
  s.lengths.resize(ne);
  s.angles.resize(nf, 3);
  s.cosines.resize(nf, 3);
  s.sines.resize(nf, 3);
  for (int v = 0; v < nv; ++v) {
    s.gamma[v] = radius_from_u(g, u[v]);
    if (!(s.gamma[v] > 0) || !std::isfinite(s.gamma[v])) {
      s.bad_vertex = v;
      return false;
    }
  }
  for (int e = 0; e < ne; ++e) {
    s.lengths[e] = circle_edge_length(g, s.gamma[t.edge_vertices(e, 0)],
                                      s.gamma[t.edge_vertices(e, 1)], eta[e]);
    if (!(s.lengths[e] > 0) || !std::isfinite(s.lengths[e])) {
      s.bad_edge = e;
      return false;
    }
  }
  s.curvature.resize(nv);
  for (int v = 0; v < nv; ++v) s.curvature[v] = t.is_boundary_vertex[v] ? M_PI : 2.0 * M_PI;
  for (int f = 0; f < nf; ++f) {
    const double l[3] = {s.lengths[t.face_edges(f, 0)], s.lengths[t.face_edges(f, 1)],
                         s.lengths[t.face_edges(f, 2)]};
    double theta[3], c[3], sn[3];
    if (!triangle_angles(g, l, theta, c, sn)) {
      s.bad_face = f;
      return false;
    }
    for (int k = 0; k < 3; ++k) {
      s.angles(f, k) = theta[k];
      s.cosines(f, k) = c[k];
      s.sines(f, k) = sn[k];
      s.curvature[t.face_vertices(f, k)] -= theta[k];
    }
  }
  return true;
}

}  // namespace ricci
