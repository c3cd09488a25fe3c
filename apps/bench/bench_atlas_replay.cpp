// `msp-bench atlas-replay METRIC`: the atlas stage alone on a flat metric saved by
// `msp-bench one-cone-one ... --save-metric METRIC` (issue 19: at 1.6M faces the flow takes a
// minute, the atlas a few seconds; the layout's accuracy can be studied on the saved metric).
// The file holds the problem's triangulation (vertex positions, faces), the lengths of each
// face's three halfedges (face_halfedges order), the targets and the root, in native binary.
#include <array>
#include <cstdint>
#include <utility>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <ricci/atlas/atlas.h>
#include <ricci/metric/polish_e2.h>
#include <ricci/topology/slice.h>

#include "bench/benchmarks.h"
#include "msp/cli.h"
#include "ricci/util/stopwatch.h"

namespace msp::bench {
namespace {

constexpr std::uint64_t kMagic = 0x4d53504d45545232ULL;  // "MSPMETR2"

template <typename T>
void put(std::ofstream& out, const T& value) {
  out.write(reinterpret_cast<const char*>(&value), sizeof(T));
}

template <typename T>
T take(std::ifstream& in) {
  T value{};
  in.read(reinterpret_cast<char*>(&value), sizeof(T));
  if (!in) throw std::runtime_error("atlas-replay: truncated metric file");
  return value;
}

}  // namespace

void save_flat_metric(const std::string& path, const ricci::Mesh& mesh, const Eigen::VectorXd& lengths,
                      const Eigen::VectorXd& lengths_low, const Eigen::VectorXd& target, int root) {
  std::ofstream out(path, std::ios::binary);
  put(out, kMagic);
  put<std::int64_t>(out, static_cast<std::int64_t>(mesh.n_vertices()));
  put<std::int64_t>(out, static_cast<std::int64_t>(mesh.n_faces()));
  put<std::int64_t>(out, root);
  for (auto v : mesh.vertices()) {
    const auto p = mesh.point(v);
    for (int k = 0; k < 3; ++k) put<double>(out, p[k]);
    put<double>(out, target[v.idx()]);
  }
  for (auto f : mesh.faces()) {
    for (auto h : ricci::face_halfedges(mesh, f)) {
      put<std::int32_t>(out, mesh.to_vertex_handle(h).idx());
      put<double>(out, lengths[mesh.edge_handle(h).idx()]);
      put<double>(out, lengths_low.size() ? lengths_low[mesh.edge_handle(h).idx()] : 0.0);
    }
  }
  if (!out) throw std::runtime_error("cannot write " + path);
}

int run_atlas_replay(int argc, char** argv) {
  Args args(argc, argv, {"polish", "double"});
  args.require_known({"polish", "double"});
  args.require_positionals(1, "msp-bench atlas-replay METRIC [--polish] [--double: without the low parts]");
  std::ifstream in(args.positionals()[0], std::ios::binary);
  const auto magic = in ? take<std::uint64_t>(in) : 0;
  const bool has_low = magic == kMagic;  // version 1 (...31) has no low parts
  if (!has_low && magic != kMagic - 1) {
    std::cerr << "atlas-replay: " << args.positionals()[0] << " is not a saved metric\n";
    return 1;
  }
  const auto n = take<std::int64_t>(in), faces = take<std::int64_t>(in), root = take<std::int64_t>(in);
  ricci::Mesh mesh;
  Eigen::VectorXd target(n);
  for (std::int64_t v = 0; v < n; ++v) {
    OpenMesh::Vec3d p;
    for (int k = 0; k < 3; ++k) p[k] = take<double>(in);
    target[v] = take<double>(in);
    mesh.add_vertex(p);
  }
  // Halfedge k of a face ends at corner k; its length goes to the edge (corner k-1, corner k).
  struct Corner {
    ricci::VertexHandle v;
    double length, low;
  };
  std::vector<std::array<Corner, 3>> saved(static_cast<size_t>(faces));
  for (auto& face : saved) {
    for (auto& corner : face) {
      corner.v = mesh.vertex_handle(take<std::int32_t>(in));
      corner.length = take<double>(in);
      corner.low = has_low ? take<double>(in) : 0.0;
    }
    if (!mesh.add_face(face[2].v, face[0].v, face[1].v).is_valid()) {
      std::cerr << "atlas-replay: a face cannot be added\n";
      return 1;
    }
  }
  Eigen::VectorXd lengths(mesh.n_edges()), low(mesh.n_edges());
  for (const auto& face : saved) {
    for (int k = 0; k < 3; ++k) {
      const auto h = mesh.find_halfedge(face[static_cast<size_t>((k + 2) % 3)].v, face[static_cast<size_t>(k)].v);
      lengths[mesh.edge_handle(h).idx()] = face[static_cast<size_t>(k)].length;
      low[mesh.edge_handle(h).idx()] = face[static_cast<size_t>(k)].low;
    }
  }
  if (args.has("double")) low = Eigen::VectorXd();
  nlohmann::json j;
  j["faces"] = faces;
  if (args.has("polish")) {
    ricci::Stopwatch t;
    const ricci::PolishE2Result p = ricci::polish_e2_lengths(mesh, lengths, target);
    j["polish_before"] = p.error_before;
    j["polish_after"] = p.error_after;
    j["polish_seconds"] = t.seconds();
    lengths = p.lengths;
    low = args.has("double") ? Eigen::VectorXd() : p.lengths_low;
  }
  ricci::Stopwatch t;
  const ricci::AffineAtlas atlas = ricci::build_affine_atlas(mesh, lengths, low, mesh.vertex_handle(static_cast<int>(root)));
  j["atlas_seconds"] = t.seconds();
  j["charts"] = atlas.charts.size();
  j["edge_error"] = atlas.layout.max_relative_length_error;
  j["domain_edge_error"] = atlas.domain_max_relative_length_error;
  j["transition"] = atlas.max_transition_residual / atlas.domain_diameter;
  j["side_pairing"] = atlas.max_side_pairing_residual / atlas.domain_diameter;
  j["relator_angle"] = atlas.relator_holonomy_angle;
  j["relator_translation"] = atlas.relator_holonomy_translation / atlas.domain_diameter;
  j["uncovered"] = atlas.uncovered_faces;
  std::cout << j.dump() << "\n";
  return 0;
}

}  // namespace msp::bench
