#include "ricci/singularity/choose.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <set>

#include <Eigen/SparseCholesky>

#include "ricci/mesh/errors.h"
#include "ricci/mesh/primitives.h"
#include "ricci/quality/distortion.h"
#include "ricci/util/stopwatch.h"

namespace ricci {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

double cot_at(const Mesh& mesh, HalfedgeHandle h) {
  // Cotangent of the corner opposite halfedge h (inside h's face).
  auto a = mesh.point(mesh.from_vertex_handle(h)), b = mesh.point(mesh.to_vertex_handle(h));
  auto c = mesh.point(mesh.to_vertex_handle(mesh.next_halfedge_handle(h)));
  auto u = a - c, v = b - c;
  return OpenMesh::dot(u, v) / std::max(OpenMesh::cross(u, v).norm(), 1e-300);
}

// Cotangent Laplacian (positive semi-definite) with weights clamped at zero: a ranking model,
// it must stay factorisable on meshes with obtuse triangles. A tiny diagonal shift removes the
// constant kernel; every right-hand side below sums to zero, so the shift does not bias u.
Eigen::SparseMatrix<double> shifted_laplacian(const Mesh& mesh) {
  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::VectorXd diagonal = Eigen::VectorXd::Zero(mesh.n_vertices());
  for (auto e : mesh.edges()) {
    double w = 0;
    for (int side = 0; side < 2; ++side) {
      auto h = mesh.halfedge_handle(e, side);
      if (!mesh.is_boundary(h)) w += 0.5 * cot_at(mesh, h);
    }
    w = std::max(w, 1e-6);
    int i = mesh.from_vertex_handle(mesh.halfedge_handle(e, 0)).idx();
    int j = mesh.to_vertex_handle(mesh.halfedge_handle(e, 0)).idx();
    triplets.emplace_back(i, j, -w);
    triplets.emplace_back(j, i, -w);
    diagonal[i] += w;
    diagonal[j] += w;
  }
  double shift = 1e-9 * diagonal.mean();
  for (int i = 0; i < diagonal.size(); ++i) triplets.emplace_back(i, i, diagonal[i] + shift);
  Eigen::SparseMatrix<double> L(diagonal.size(), diagonal.size());
  L.setFromTriplets(triplets.begin(), triplets.end());
  return L;
}

Eigen::VectorXd angle_defects(const Mesh& mesh) {
  Eigen::VectorXd K(mesh.n_vertices());
  for (auto v : mesh.vertices()) {
    double sum = 0;
    for (auto h : mesh.voh_range(v)) {
      if (!mesh.is_boundary(h)) sum += mesh.calc_sector_angle(mesh.prev_halfedge_handle(h));
    }
    K[v.idx()] = (mesh.is_boundary(v) ? M_PI : 2 * M_PI) - sum;
  }
  return K;
}

// Predicted area distortion of the log-scale field u: faces scale by exp(2 * mean u).
double predicted_distortion(const Eigen::VectorXd& u, const Eigen::VectorXd& log_area,
                            const Eigen::MatrixX3i& faces) {
  Eigen::VectorXd d(faces.rows());
  for (int f = 0; f < faces.rows(); ++f) d[f] = -2.0 / 3.0 * (u[faces(f, 0)] + u[faces(f, 1)] + u[faces(f, 2)]);
  // log(S/sum S) - log(s/sum s) = d - log(sum S) + log(sum S e^{-d}); normalise in log space.
  double peak = (log_area - d).maxCoeff();
  double log_flat_total = peak + std::log((log_area - d).array().unaryExpr([&](double x) { return std::exp(x - peak); }).sum());
  double peak2 = log_area.maxCoeff();
  double log_total = peak2 + std::log((log_area.array() - peak2).exp().sum());
  Eigen::ArrayXd r = d.array() - log_total + log_flat_total;
  return r.square().mean();
}

std::vector<int> ranked_vertex_pool(const Mesh& mesh, int limit) {
  std::vector<int> pool(mesh.n_vertices());
  std::iota(pool.begin(), pool.end(), 0);
  pool.erase(std::remove_if(pool.begin(), pool.end(),
                            [&](int v) { return mesh.is_boundary(mesh.vertex_handle(v)); }),
             pool.end());
  if (static_cast<int>(pool.size()) > limit) {
    std::mt19937 rng(12345);
    std::shuffle(pool.begin(), pool.end(), rng);
    pool.resize(static_cast<size_t>(limit));
  }
  return pool;
}

}  // namespace

std::vector<SingularityScore> rank_singularities(const Mesh& mesh, const SingularityOptions& options) {
  const int n = static_cast<int>(mesh.n_vertices());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(shifted_laplacian(mesh));
  if (solver.info() != Eigen::Success) throw SolverError("singularity ranking: Laplacian factorisation failed");
  const double cone = 2.0 * M_PI * surface_topology(mesh).euler_characteristic;
  Eigen::VectorXd base_rhs = -angle_defects(mesh);
  base_rhs.array() += cone / n;  // with the cone's mean removed, the right-hand side sums to 0
  Eigen::VectorXd u0 = solver.solve(base_rhs);
  Eigen::MatrixX3i faces(mesh.n_faces(), 3);
  Eigen::VectorXd log_area(mesh.n_faces());
  for (auto f : mesh.faces()) {
    int k = 0;
    for (auto v : mesh.fv_range(f)) faces(f.idx(), k++) = v.idx();
    log_area[f.idx()] = std::log(std::max(mesh.calc_face_area(f), 1e-300));
  }
  std::vector<SingularityScore> scores;
  Eigen::VectorXd unit = Eigen::VectorXd::Constant(n, -1.0 / n);
  for (int p : ranked_vertex_pool(mesh, options.max_ranked_vertices)) {
    unit[p] += 1.0;
    Eigen::VectorXd u = u0 + cone * solver.solve(unit);
    unit[p] -= 1.0;
    scores.push_back({p, predicted_distortion(u, log_area, faces)});
  }
  std::sort(scores.begin(), scores.end(),
            [](const SingularityScore& a, const SingularityScore& b) { return a.area_distortion < b.area_distortion; });
  return scores;
}

double one_cone_area_distortion(const Mesh& mesh, int vertex, const SingularityOptions& options) {
  OneConeProblem problem = prepare_one_cone(mesh, vertex, options.valence, false);
  FlowResult result = solve_one_cone_flow(problem, options.flow, options.keep_metric);
  if (!result.converged()) return kInfinity;
  return measure_distortion(problem.mesh, result.lengths).area_distortion;
}

int verified_count(int vertices, const SingularityOptions& options) {
  // Small meshes: one flow per 20 vertices, but no more than about 4e4 / V flows (each costs
  // O(V)), so the extra checks fade out by a few thousand vertices.
  const int extra = std::min(vertices / 20, static_cast<int>(4e4 / std::max(vertices, 1)));
  return std::max(options.verified_candidates, extra);
}

SingularityChoice choose_singularity(const Mesh& mesh, const SingularityOptions& options) {
  const Stopwatch start;
  SingularityChoice choice;
  if (!needs_singular_vertex(mesh)) {
    choice.area_distortion = one_cone_area_distortion(mesh, -1, options);
    choice.flows_run = 1;
  } else {
    std::set<int> checked;
    auto verify = [&](int v) {
      if (!checked.insert(v).second) return;
      choice.verified.push_back({v, one_cone_area_distortion(mesh, v, options)});
      ++choice.flows_run;
    };
    std::vector<SingularityScore> ranked = rank_singularities(mesh, options);
    const int count = verified_count(static_cast<int>(mesh.n_vertices()), options);
    for (int i = 0; i < std::min<int>(count, static_cast<int>(ranked.size())); ++i) {
      verify(ranked[static_cast<size_t>(i)].vertex);
    }
    auto score_of = [&](int v) {
      for (const auto& s : choice.verified) {
        if (s.vertex == v) return s.area_distortion;
      }
      return kInfinity;
    };
    auto descend = [&](int centre) {
      for (int round = 0; round < 10; ++round) {
        int next = centre;
        for (auto w : mesh.vv_range(mesh.vertex_handle(centre))) {
          if (mesh.is_boundary(w)) continue;
          verify(w.idx());
          if (score_of(w.idx()) < score_of(next)) next = w.idx();
        }
        if (next == centre) break;
        centre = next;
      }
    };
    auto best = [&] {
      return *std::min_element(choice.verified.begin(), choice.verified.end(),
                               [](const SingularityScore& a, const SingularityScore& b) {
                                 return a.area_distortion < b.area_distortion;
                               });
    };
    if (options.refine_in_one_ring && !choice.verified.empty()) {
      // Greedy descent over one-rings from the best few verified vertices (the linear model
      // can misjudge a whole region, so one basin is not enough), each until its vertex beats
      // all its neighbours.
      std::vector<SingularityScore> starts = choice.verified;
      std::sort(starts.begin(), starts.end(), [](const SingularityScore& a, const SingularityScore& b) {
        return a.area_distortion < b.area_distortion;
      });
      starts.resize(std::min<std::size_t>(starts.size(), static_cast<std::size_t>(options.descent_starts)));
      for (const SingularityScore& start : starts) {
        if (!std::isfinite(start.area_distortion)) continue;
        descend(start.vertex);
      }
    }
    if (choice.verified.empty() || !std::isfinite(best().area_distortion)) {
      throw SolverError("no candidate singular vertex gave a converging flow; try valence options or another metric");
    }
    choice.vertex = best().vertex;
    choice.area_distortion = best().area_distortion;
  }
  choice.seconds = start.seconds();
  return choice;
}

}  // namespace ricci
