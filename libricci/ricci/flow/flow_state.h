#pragma once
// The quantities the flow recomputes at every trial point u: radii, lengths, corner angles (with
// their cosines and sines, reused by the Hessian) and vertex curvature.
#include <Eigen/Core>

#include "ricci/metric/geometry.h"
#include "ricci/metric/mesh_tables.h"

namespace ricci {

struct FlowState {
  Eigen::VectorXd u;
  Eigen::VectorXd gamma;
  EdgeLengths lengths;
  Eigen::MatrixX3d angles, cosines, sines;
  Eigen::VectorXd curvature;
  /// Where the last evaluation failed: a vertex whose radius is out of range, an edge without a
  /// length, or a face violating the triangle inequality (-1 when not applicable).
  int bad_vertex = -1, bad_edge = -1, bad_face = -1;
};

/// Evaluates `state` at flow variables u with fixed edge quantities eta. Returns false at the
/// first invalid radius, edge or triangle (recorded in state.bad_*); the other fields are then
/// partly updated and must not be used.
bool evaluate_flow_state(const MeshTables& tables, Geometry geometry, const Eigen::VectorXd& eta,
                         const Eigen::VectorXd& u, FlowState& state);

}  // namespace ricci
