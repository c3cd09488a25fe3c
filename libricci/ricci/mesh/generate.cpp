// The CGAL-free part of the generator: quality measure and descriptions.
#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "ricci/mesh/generate.h"

namespace ricci {

double min_corner_angle_degrees(const Mesh& mesh) {
  double smallest = M_PI;
  for (auto f : mesh.faces()) {
    std::array<OpenMesh::Vec3d, 3> p;
    int k = 0;
    for (auto v : f.vertices()) p[k++] = mesh.point(v);
    for (int i = 0; i < 3; ++i) {
      const OpenMesh::Vec3d a = p[(i + 1) % 3] - p[i];
      const OpenMesh::Vec3d b = p[(i + 2) % 3] - p[i];
      smallest = std::min(smallest, std::atan2(OpenMesh::cross(a, b).norm(), OpenMesh::dot(a, b)));
    }
  }
  return smallest * 180 / M_PI;
}

std::string describe_surface(const GenerateOptions& options) {
  std::string shape = options.genus == 0 ? "smooth blob (3 fused spheres)"
                      : options.genus == 1
                          ? "torus R=1 r=0.35"
                          : std::to_string(options.genus) + " fused tori R=1 r=0.35 in a row";
  const std::string g = "genus " + std::to_string(options.genus) + " ";
  if (options.holes == 0) return g + "closed " + shape;
  return g + shape + " with " + std::to_string(options.holes) + " end cap(s) cut off";
}

}  // namespace ricci
