#pragma once
// The one mesh type used across the library: an OpenMesh triangle mesh in double precision.
// Geometry that algorithms change (edge lengths, radii, layouts) lives in Eigen vectors indexed
// by element index, never inside the mesh.
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

namespace ricci {

struct MeshTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
  VertexAttributes(OpenMesh::Attributes::Status);
  EdgeAttributes(OpenMesh::Attributes::Status);
  FaceAttributes(OpenMesh::Attributes::Status);
  HalfedgeAttributes(OpenMesh::Attributes::PrevHalfedge);
};

using Mesh = OpenMesh::TriMesh_ArrayKernelT<MeshTraits>;
using VertexHandle = Mesh::VertexHandle;
using HalfedgeHandle = Mesh::HalfedgeHandle;
using EdgeHandle = Mesh::EdgeHandle;
using FaceHandle = Mesh::FaceHandle;

/// #V by 3 vertex positions and #F by 3 vertex indices: the libigl-style view of a mesh.
struct VertexFaceArrays {
  Eigen::MatrixX3d V;
  Eigen::MatrixX3i F;
};

inline Eigen::Vector3d to_eigen(const OpenMesh::Vec3d& p) { return {p[0], p[1], p[2]}; }
inline OpenMesh::Vec3d to_openmesh(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }

/// V - E + F of the mesh as stored (unreferenced vertices count).
inline int euler_characteristic(const Mesh& mesh) {
  return static_cast<int>(mesh.n_vertices()) - static_cast<int>(mesh.n_edges()) +
         static_cast<int>(mesh.n_faces());
}

/// Angle in [0, pi] between two vectors (normals, corner edges). atan2 of |a x b| and a . b stays
/// accurate for tiny angles, where acos of the normalised dot product does not.
inline double angle_between(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

}  // namespace ricci
