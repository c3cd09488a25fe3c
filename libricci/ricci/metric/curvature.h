#pragma once
// Corner angles, vertex curvature, face areas and the Gauss-Bonnet check of a discrete metric
// (edge lengths) in a background geometry (Ricci-flow paper §IV).
#include <Eigen/Core>

#include "ricci/mesh/mesh.h"
#include "ricci/metric/geometry.h"
#include "ricci/metric/mesh_tables.h"

namespace ricci {

/// #F by 3 corner angles; column k is the angle at tables.face_vertices(f, k).
/// \throw InvalidInputError naming the first face whose lengths violate the triangle inequality
///        (or, in S2, whose perimeter reaches 2π), or a non-finite length.
[[nodiscard]] Eigen::MatrixX3d corner_angles(const MeshTables& tables, const EdgeLengths& lengths,
                                             Geometry geometry);

/// Discrete Gaussian curvature per vertex: 2π - Σθ inside, π - Σθ on the boundary (the
/// boundary value is the discrete geodesic curvature). \throw as corner_angles.
[[nodiscard]] Eigen::VectorXd vertex_curvature(const MeshTables& tables,
                                               const EdgeLengths& lengths, Geometry geometry);

/// Curvature from precomputed corner angles.
[[nodiscard]] Eigen::VectorXd vertex_curvature(const MeshTables& tables,
                                               const Eigen::MatrixX3d& angles);

/// Face areas in the background geometry (Heron in E2, angle defect/excess in H2/S2).
[[nodiscard]] Eigen::VectorXd face_areas(const MeshTables& tables, const EdgeLengths& lengths,
                                         Geometry geometry);

/// Σ K_i + λ Σ A_f - 2πχ with λ = 0 (E2), -1 (H2), +1 (S2): zero up to rounding for any valid
/// metric; a test of the curvature code and of the mesh's topology bookkeeping.
[[nodiscard]] double gauss_bonnet_residual(const MeshTables& tables, const EdgeLengths& lengths,
                                           Geometry geometry);

/// Convenience overloads on a mesh (build the tables on each call).
[[nodiscard]] Eigen::VectorXd vertex_curvature(const Mesh& mesh, const EdgeLengths& lengths,
                                               Geometry geometry);
[[nodiscard]] double gauss_bonnet_residual(const Mesh& mesh, const EdgeLengths& lengths,
                                           Geometry geometry);

}  // namespace ricci
