// diagnose(): every count of MeshDiagnosis in a few linear passes plus two sorts, so a
// 100k-face mesh takes tens of milliseconds.
#include "ricci/mesh/diagnose.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/Geometry>

#include "ricci/mesh/topology_util.h"
#include "ricci/util/hash.h"

namespace ricci {
namespace {

using detail::DisjointSets;
using detail::EdgeTable;
using std::size_t;

std::string edge_name(int a, int b) {
  return "edge (" + std::to_string(a) + ", " + std::to_string(b) + ")";
}

std::string number_text(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

void add_problem(MeshDiagnosis& d, MeshProblemKind kind, int count, std::string message,
                 const char* plural) {
  if (count > 1) message += " (" + std::to_string(count) + " " + plural + " in all)";
  d.problems.push_back({kind, count, std::move(message)});
}

/// Shared state of one diagnosis pass.
struct Context {
  const PolygonSoup& soup;
  MeshDiagnosis& d;
  std::vector<char> use_face;  // enters the topology: valid indices, none repeated
  std::vector<char> referenced;
  EdgeTable edges;
};

/// Bounding box over finite positions; reports the first referenced non-finite vertex (an
/// unreferenced one is harmless: build_mesh() strips it).
void check_coordinates(Context& c) {
  const auto& positions = c.soup.positions;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
  int first_bad = -1, referenced_bad = 0;
  for (size_t v = 0; v < positions.size(); ++v) {
    if (positions[v].allFinite()) {
      lo = lo.cwiseMin(positions[v]);
      hi = hi.cwiseMax(positions[v]);
      continue;
    }
    ++c.d.non_finite_vertices;
    if (!c.referenced[v]) continue;
    ++referenced_bad;
    if (first_bad < 0) first_bad = static_cast<int>(v);
  }
  c.d.bbox_diagonal = (hi - lo).allFinite() ? (hi - lo).norm() : 0.0;
  if (first_bad < 0) return;
  const auto& p = positions[first_bad];
  add_problem(c.d, MeshProblemKind::non_finite_coordinate, referenced_bad,
              c.soup.vertex_where(first_bad) + " has a non-finite coordinate (" +
                  number_text(p.x()) + ", " + number_text(p.y()) + ", " + number_text(p.z()) + ")",
              "such vertices");
}

/// Sorts faces into used / bad / repeated-index and marks referenced vertices.
void classify_faces(Context& c) {
  const auto& faces = c.soup.faces;
  const int n = static_cast<int>(c.soup.positions.size());
  c.use_face.assign(faces.size(), 1);
  c.referenced.assign(c.soup.positions.size(), 0);
  int first_bad = -1, first_repeat = -1, repeats = 0;
  std::vector<int> sorted;
  for (size_t f = 0; f < faces.size(); ++f) {
    const auto& face = faces[f];
    if (face.size() != 3) ++c.d.non_triangle_faces;
    const bool bad = face.size() < 3 ||
                     std::any_of(face.begin(), face.end(), [n](int i) { return i < 0 || i >= n; });
    if (bad) {
      ++c.d.bad_faces;
      if (first_bad < 0) first_bad = static_cast<int>(f);
      c.use_face[f] = 0;
      continue;
    }
    sorted.assign(face.begin(), face.end());
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) {
      ++repeats;
      if (first_repeat < 0) first_repeat = static_cast<int>(f);
      c.use_face[f] = 0;
      continue;
    }
    for (int v : face) c.referenced[v] = 1;
  }
  c.d.degenerate_faces += repeats;
  if (first_bad >= 0)
    add_problem(c.d, MeshProblemKind::bad_face, c.d.bad_faces,
                c.soup.face_where(first_bad) +
                    " has fewer than 3 vertices or an index outside [0, " + std::to_string(n) + ")",
                "such faces");
  if (std::count(c.use_face.begin(), c.use_face.end(), 1) == 0)
    add_problem(c.d, MeshProblemKind::no_faces, 1, "no usable faces", "");
  if (first_repeat >= 0)
    add_problem(c.d, MeshProblemKind::repeated_index, repeats,
                c.soup.face_where(first_repeat) + " is degenerate: it repeats a vertex index",
                "such faces");
  for (char r : c.referenced) c.d.referenced_vertices += r;
  c.d.unreferenced_vertices = c.d.vertices - c.d.referenced_vertices;
}

/// Edge counts, edge-manifoldness and consistent orientation, from the edge table.
void check_edges(Context& c) {
  const EdgeTable& table = c.edges;
  c.d.edges = static_cast<int>(table.edge_count());
  size_t first_fin = SIZE_MAX;
  for (size_t e = 0; e < table.edge_count(); ++e) {
    const size_t sides = table.side_count(e);
    if (sides == 1) ++c.d.boundary_edges;
    if (sides > 2) {
      ++c.d.non_manifold_edges;
      if (first_fin == SIZE_MAX) first_fin = e;
    }
    int forward = 0;
    for (size_t k = 0; k < sides; ++k) forward += table.side(e, k).from == table.low(e);
    if (forward > 1 || static_cast<int>(sides) - forward > 1) c.d.consistently_oriented = false;
  }
  c.d.edge_manifold = c.d.non_manifold_edges == 0;
  if (first_fin == SIZE_MAX) return;
  const size_t sides = table.side_count(first_fin);
  std::string faces;
  for (size_t k = 0; k < sides && k < 6; ++k)
    faces += (k ? ", " : "") + std::to_string(table.side(first_fin, k).face);
  if (sides > 6) faces += ", ...";
  add_problem(c.d, MeshProblemKind::non_manifold_edge, c.d.non_manifold_edges,
              edge_name(table.low(first_fin), table.high(first_fin)) + " is shared by " +
                  std::to_string(sides) + " faces (faces " + faces + ")",
              "non-manifold edges");
}

/// 2-colours faces by "flipped or not" across every 2-face edge; a clash means non-orientable.
void check_orientability(Context& c) {
  const EdgeTable& table = c.edges;
  const int conflict_edge = colour_orientation(table, c.soup.faces.size(), c.use_face).conflict_edge;
  c.d.orientable = conflict_edge < 0;
  if (conflict_edge >= 0)
    add_problem(c.d, MeshProblemKind::non_orientable, 1,
                "non-orientable: orientation conflict at " +
                    edge_name(table.low(conflict_edge), table.high(conflict_edge)),
                "");
}

/// A vertex is manifold when its faces form one fan: the link edges (prev, next) of its corners
/// connect all its neighbours.
void check_vertex_fans(Context& c) {
  const auto& faces = c.soup.faces;
  const size_t n = c.soup.positions.size();
  std::vector<size_t> begin(n + 1, 0);
  for (size_t f = 0; f < faces.size(); ++f)
    if (c.use_face[f])
      for (int v : faces[f]) ++begin[v + 1];
  for (size_t v = 0; v < n; ++v) begin[v + 1] += begin[v];
  std::vector<std::pair<int, int>> corners(begin.back());  // (prev, next) around each vertex
  std::vector<size_t> fill(begin.begin(), begin.end() - 1);
  for (size_t f = 0; f < faces.size(); ++f) {
    if (!c.use_face[f]) continue;
    const auto& face = faces[f];
    const size_t m = face.size();
    for (size_t k = 0; k < m; ++k)
      corners[fill[face[k]]++] = {face[(k + m - 1) % m], face[(k + 1) % m]};
  }
  int first_pinched = -1, first_fans = 0;
  std::vector<int> neighbours;
  for (size_t v = 0; v < n; ++v) {
    if (begin[v + 1] - begin[v] < 2) continue;
    neighbours.clear();
    for (size_t k = begin[v]; k < begin[v + 1]; ++k) {
      neighbours.push_back(corners[k].first);
      neighbours.push_back(corners[k].second);
    }
    std::sort(neighbours.begin(), neighbours.end());
    neighbours.erase(std::unique(neighbours.begin(), neighbours.end()), neighbours.end());
    auto local = [&](int u) {
      return static_cast<int>(std::lower_bound(neighbours.begin(), neighbours.end(), u) -
                              neighbours.begin());
    };
    DisjointSets link(neighbours.size());
    int fans = static_cast<int>(neighbours.size());
    for (size_t k = begin[v]; k < begin[v + 1]; ++k)
      fans -= link.unite(local(corners[k].first), local(corners[k].second));
    if (fans <= 1) continue;
    ++c.d.non_manifold_vertices;
    if (first_pinched < 0) {
      first_pinched = static_cast<int>(v);
      first_fans = fans;
    }
  }
  c.d.vertex_manifold = c.d.non_manifold_vertices == 0;
  if (first_pinched >= 0)
    add_problem(c.d, MeshProblemKind::non_manifold_vertex, c.d.non_manifold_vertices,
                "vertex " + std::to_string(first_pinched) + " is pinched: its faces form " +
                    std::to_string(first_fans) + " fans",
                "non-manifold vertices");
}

/// Components through shared vertices, boundary loops as components of the boundary edges,
/// then chi and genus.
void count_topology(Context& c) {
  const auto& faces = c.soup.faces;
  const size_t n = c.soup.positions.size();
  DisjointSets parts(n);
  int used_faces = 0;
  for (size_t f = 0; f < faces.size(); ++f) {
    if (!c.use_face[f]) continue;
    ++used_faces;
    for (size_t k = 1; k < faces[f].size(); ++k) parts.unite(faces[f][0], faces[f][k]);
  }
  std::vector<int> size_of_part(n, 0);
  for (size_t v = 0; v < n; ++v)
    if (c.referenced[v] && size_of_part[parts.find(static_cast<int>(v))]++ == 0) ++c.d.components;
  DisjointSets loops(n);
  std::vector<char> on_boundary(n, 0);
  for (size_t e = 0; e < c.edges.edge_count(); ++e) {
    if (c.edges.side_count(e) != 1) continue;
    loops.unite(c.edges.low(e), c.edges.high(e));
    on_boundary[c.edges.low(e)] = on_boundary[c.edges.high(e)] = 1;
  }
  for (size_t v = 0; v < n; ++v)
    if (on_boundary[v] && loops.find(static_cast<int>(v)) == static_cast<int>(v))
      ++c.d.boundary_loops;
  c.d.euler_characteristic = c.d.referenced_vertices - c.d.edges + used_faces;
  c.d.genus = (2.0 * c.d.components - c.d.boundary_loops - c.d.euler_characteristic) / 2.0;
  if (c.d.components > 1) {
    std::vector<int> sizes;
    for (int s : size_of_part)
      if (s > 0) sizes.push_back(s);
    std::sort(sizes.rbegin(), sizes.rend());
    std::string list;
    for (size_t k = 0; k < sizes.size() && k < 4; ++k)
      list += (k ? ", " : "") + std::to_string(sizes[k]);
    if (sizes.size() > 4) list += ", ...";
    c.d.problems.push_back(
        {MeshProblemKind::several_components, c.d.components,
         std::to_string(c.d.components) + " connected components (vertex counts " + list + ")"});
  }
}

/// Counts vertices at exactly the position of another (finite positions only: NaN breaks sorting).
void count_duplicate_vertices(Context& c) {
  const auto& p = c.soup.positions;
  std::vector<int> order;
  order.reserve(p.size());
  for (size_t v = 0; v < p.size(); ++v)
    if (p[v].allFinite()) order.push_back(static_cast<int>(v));
  auto less = [&p](int a, int b) {
    return std::lexicographical_compare(p[a].data(), p[a].data() + 3, p[b].data(), p[b].data() + 3);
  };
  std::sort(order.begin(), order.end(), less);
  for (size_t k = 1; k < order.size(); ++k)
    c.d.duplicate_vertices += p[order[k - 1]] == p[order[k]];
}

/// Faces on the same vertex set, found by sorting (hash of the sorted face, face) pairs and
/// comparing the faces of equal hashes exactly.
void count_duplicate_faces(Context& c) {
  const auto& faces = c.soup.faces;
  std::vector<std::pair<uint64_t, int>> keyed;
  std::vector<int> sorted_a, sorted_b;
  for (size_t f = 0; f < faces.size(); ++f) {
    if (!c.use_face[f]) continue;
    sorted_a.assign(faces[f].begin(), faces[f].end());
    std::sort(sorted_a.begin(), sorted_a.end());
    Fnv1a hash;
    for (int v : sorted_a) hash.add(static_cast<uint32_t>(v));
    keyed.push_back({hash.value(), static_cast<int>(f)});
  }
  std::sort(keyed.begin(), keyed.end());
  auto same_set = [&](int f, int g) {
    if (faces[f].size() != faces[g].size()) return false;
    sorted_a.assign(faces[f].begin(), faces[f].end());
    sorted_b.assign(faces[g].begin(), faces[g].end());
    std::sort(sorted_a.begin(), sorted_a.end());
    std::sort(sorted_b.begin(), sorted_b.end());
    return sorted_a == sorted_b;
  };
  int first_a = -1, first_b = -1;
  std::vector<int> representatives;
  for (size_t i = 0; i < keyed.size();) {
    size_t j = i + 1;
    while (j < keyed.size() && keyed[j].first == keyed[i].first) ++j;
    // Within a run of equal hashes (nearly always one vertex set), compare with the distinct
    // sets seen so far in the run; a face equal to one of them is a duplicate.
    representatives.assign(1, keyed[i].second);
    for (size_t k = i + 1; k < j; ++k) {
      const int f = keyed[k].second;
      const auto match = std::find_if(representatives.begin(), representatives.end(),
                                      [&](int g) { return same_set(g, f); });
      if (match == representatives.end()) {
        representatives.push_back(f);
        continue;
      }
      ++c.d.duplicate_faces;
      if (first_b < 0 || f < first_b) {
        first_a = *match;
        first_b = f;
      }
    }
    i = j;
  }
  if (first_a >= 0)
    add_problem(
        c.d, MeshProblemKind::duplicate_face, c.d.duplicate_faces,
        c.soup.face_where(first_b) + " has the same vertices as " + c.soup.face_where(first_a),
        "duplicate faces");
}

/// Zero-area faces and the smallest triangle angle. A face is degenerate when its area is at most
/// 1e-12 * (longest side)^2, i.e. its corners are collinear to 12 digits (or coincide). The test
/// is scale-invariant and judges shape, not size: a tiny well-shaped triangle (marching-cubes
/// meshes have them) is fine for the pipeline, a needle with collinear corners is not.
void measure_faces(Context& c) {
  const auto& p = c.soup.positions;
  double min_cos_angle = 2;  // cosine of the smallest angle seen; 2 = none yet
  int first_zero = -1, zero = 0;
  for (size_t f = 0; f < c.soup.faces.size(); ++f) {
    if (!c.use_face[f]) continue;
    const auto& face = c.soup.faces[f];
    Eigen::Vector3d area = Eigen::Vector3d::Zero();
    double longest_squared = 0;
    for (size_t k = 0; k < face.size(); ++k) {
      longest_squared =
          std::max(longest_squared, (p[face[(k + 1) % face.size()]] - p[face[k]]).squaredNorm());
      if (k >= 1 && k + 1 < face.size())
        area += (p[face[k]] - p[face[0]]).cross(p[face[k + 1]] - p[face[0]]);
    }
    if (0.5 * area.norm() <= 1e-12 * longest_squared) {  // false for NaN: reported apart
      ++zero;
      if (first_zero < 0) first_zero = static_cast<int>(f);
    }
    if (face.size() != 3) continue;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d a = p[face[(k + 1) % 3]] - p[face[k]];
      const Eigen::Vector3d b = p[face[(k + 2) % 3]] - p[face[k]];
      const double denominator = a.norm() * b.norm();
      const double cosine = denominator > 0 ? a.dot(b) / denominator : 1.0;
      if (std::isfinite(cosine) && (min_cos_angle > 1.5 || cosine > min_cos_angle))
        min_cos_angle = std::min(1.0, cosine);
    }
  }
  c.d.min_angle_deg = min_cos_angle > 1.5 ? 0.0 : std::acos(min_cos_angle) * 180.0 / M_PI;
  c.d.degenerate_faces += zero;
  if (first_zero >= 0)
    add_problem(c.d, MeshProblemKind::zero_area, zero,
                c.soup.face_where(first_zero) + " has zero area", "such faces");
}

}  // namespace

bool MeshDiagnosis::clean_manifold() const {
  const bool has_faces = faces > bad_faces;
  return has_faces && edge_manifold && vertex_manifold && orientable && bad_faces == 0 &&
         duplicate_faces == 0 &&
         std::none_of(problems.begin(), problems.end(), [](const MeshProblem& p) {
           return p.kind == MeshProblemKind::repeated_index;
         });
}

MeshDiagnosis diagnose(const PolygonSoup& soup) {
  MeshDiagnosis d;
  d.vertices = static_cast<int>(soup.positions.size());
  d.faces = static_cast<int>(soup.faces.size());
  Context c{soup, d, {}, {}, {}};
  classify_faces(c);
  check_coordinates(c);
  c.edges = detail::build_edge_table(soup.faces, c.use_face);
  check_edges(c);
  check_vertex_fans(c);
  check_orientability(c);
  count_duplicate_faces(c);
  count_topology(c);
  count_duplicate_vertices(c);
  measure_faces(c);
  // The first problem is the headline (msp info --strict, build_mesh): most basic kind first.
  std::stable_sort(d.problems.begin(), d.problems.end(),
                   [](const MeshProblem& a, const MeshProblem& b) { return a.kind < b.kind; });
  return d;
}

}  // namespace ricci
