#pragma once
// Whether every face's neighbourhood (the faces sharing a vertex with it) is a topological disk.
// A DMS spline needs each face's neighbourhood in one planar chart; on meshes with handles only
// a few edges thick (CAD models, coarse domains) the neighbourhood is an annulus around the
// handle and no chart can hold it. Refining the mesh (midpoint subdivision) doubles every
// handle's circumference in edges and cures it.
#include <vector>

#include "ricci/mesh/mesh.h"

namespace ricci {

/// By face: 1 when the face's neighbourhood has Euler characteristic other than 1 (not a disk).
[[nodiscard]] std::vector<char> non_disk_face_neighbourhoods(const Mesh& mesh);

/// The number of faces flagged by non_disk_face_neighbourhoods.
[[nodiscard]] int count_non_disk_face_neighbourhoods(const Mesh& mesh);

}  // namespace ricci
