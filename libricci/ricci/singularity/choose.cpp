#include "ricci/singularity/choose.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <map>
#include <mutex>
#include <numeric>
#include <optional>
#include <set>
#include <vector>

#include "ricci/flow/linear_solver.h"
#include "ricci/mesh/errors.h"
#include "ricci/mesh/primitives.h"
#include "ricci/quality/distortion.h"
#include "ricci/util/parallel.h"
#include "ricci/util/stopwatch.h"

namespace ricci {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Right-hand sides solved together (one blocked back-substitution)...
constexpr int kBlockColumns = 32;
// ...at most this many doubles per block: a block lives in three copies (the right-hand sides
// solved in place, and for each thread's columns CHOLMOD's workspace and its solution), beside
// the factor and the input mesh: this is the choice's memory peak at 1.6M faces, which 6.5M
// doubles (8 columns at 800k vertices, ~150 MB) keep below the flow's (docs/design-notes.md,
// "The 1.6M-face atlas under 1.2 GB"). Every block passes over the whole factor, so there are
// as few as the bound allows, of even sizes; below 200k vertices the 32 columns rule.
constexpr double kBlockDoubles = 6.5e6;

int block_columns(int vertices) {
  return std::clamp(static_cast<int>(kBlockDoubles / std::max(vertices, 1)), 1, kBlockColumns);
}

double cot_at(const Mesh& mesh, HalfedgeHandle h) {
  // Cotangent of the corner opposite halfedge h (inside h's face).
  auto a = mesh.point(mesh.from_vertex_handle(h)), b = mesh.point(mesh.to_vertex_handle(h));
  auto c = mesh.point(mesh.to_vertex_handle(mesh.next_halfedge_handle(h)));
  auto u = a - c, v = b - c;
  return OpenMesh::dot(u, v) / std::max(OpenMesh::cross(u, v).norm(), 1e-300);
}

// Lower triangle of the cotangent Laplacian (positive semi-definite) with weights clamped at
// zero: a ranking model, it must stay factorisable on meshes with obtuse triangles. A tiny
// diagonal shift removes the constant kernel; every right-hand side below sums to zero, so the
// shift does not bias u.
Eigen::SparseMatrix<double> shifted_laplacian(const Mesh& mesh) {
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(mesh.n_edges() + mesh.n_vertices());
  Eigen::VectorXd diagonal = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(mesh.n_vertices()));
  for (auto e : mesh.edges()) {
    double w = 0;
    for (int side = 0; side < 2; ++side) {
      auto h = mesh.halfedge_handle(e, side);
      if (!mesh.is_boundary(h)) w += 0.5 * cot_at(mesh, h);
    }
    w = std::max(w, 1e-6);
    const int i = mesh.from_vertex_handle(mesh.halfedge_handle(e, 0)).idx();
    const int j = mesh.to_vertex_handle(mesh.halfedge_handle(e, 0)).idx();
    triplets.emplace_back(std::max(i, j), std::min(i, j), -w);
    diagonal[i] += w;
    diagonal[j] += w;
  }
  const double shift = 1e-9 * diagonal.mean();
  for (int i = 0; i < diagonal.size(); ++i) triplets.emplace_back(i, i, diagonal[i] + shift);
  Eigen::SparseMatrix<double> L(diagonal.size(), diagonal.size());
  L.setFromTriplets(triplets.begin(), triplets.end());
  L.makeCompressed();
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

// The linearised one-cone model: one factorisation, one back-substitution per candidate.
class LinearModel {
 public:
  // The factorisation (serial CHOLMOD) runs beside the model's per-vertex and per-face data,
  // which do not need it, on a second thread.
  LinearModel(const Mesh& mesh, int euler_characteristic)
      : n_(static_cast<int>(mesh.n_vertices())),
        solver_(resolve_linear_solver(LinearSolver::automatic, n_)),
        cone_(2.0 * M_PI * euler_characteristic) {
    bool factored = false;
    run_workers(2, [&](int t) {
      if (t == 0) {
        const Eigen::SparseMatrix<double> L = shifted_laplacian(mesh);
        solver_.analyze(L);
        factored = solver_.factorize(L);
        return;
      }
      base_rhs_ = -angle_defects(mesh);
      base_rhs_.array() += cone_ / n_;  // with the cone's mean removed, the rhs sums to 0
      faces_.resize(static_cast<Eigen::Index>(mesh.n_faces()), 3);
      log_area_.resize(static_cast<Eigen::Index>(mesh.n_faces()));
      for (auto f : mesh.faces()) {
        int k = 0;
        for (auto v : mesh.fv_range(f)) faces_(f.idx(), k++) = v.idx();
        log_area_[f.idx()] = std::log(std::max(mesh.calc_face_area(f), 1e-300));
      }
      const double peak = log_area_.maxCoeff();
      log_total_ = peak + std::log((log_area_.array() - peak).exp().sum());
    });
    if (!factored) throw SolverError("singularity ranking: Laplacian factorisation failed");
  }

  // Predicted area distortion of a cone at each vertex (cached). The model's own solution
  // u0 (the mesh's curvature alone) rides in the first block as an extra, last column.
  std::vector<double> score(const std::vector<int>& vertices) {
    std::vector<int> todo;
    for (int p : vertices) {
      if (!cache_.count(p) && std::find(todo.begin(), todo.end(), p) == todo.end()) {
        todo.push_back(p);
      }
    }
    const size_t most = static_cast<size_t>(block_columns(n_));
    const size_t blocks = (todo.size() + most - 1) / most;
    const size_t block = blocks > 0 ? (todo.size() + blocks - 1) / blocks : most;
    for (size_t start = 0; start < todo.size(); start += block) {
      const size_t count = std::min<size_t>(block, todo.size() - start);
      const bool with_u0 = u0_.size() == 0;
      const auto columns = static_cast<Eigen::Index>(count + (with_u0 ? 1 : 0));
      Eigen::MatrixXd rhs = Eigen::MatrixXd::Constant(n_, columns, -1.0 / n_);
      for (size_t j = 0; j < count; ++j) rhs(todo[start + j], static_cast<Eigen::Index>(j)) += 1.0;
      if (with_u0) rhs.col(columns - 1) = base_rhs_;
      solver_.solve_columns_in_place(rhs);
      const Eigen::MatrixXd& green = rhs;
      if (with_u0) u0_ = green.col(columns - 1);
      solves_ += static_cast<int>(columns);
      // Each column's score on one thread (the same sums on any number of threads).
      std::vector<double> scores(count);
      const int workers = std::min(requested_threads(0), static_cast<int>(count));
      run_workers(workers, [&](int t) {
        for (size_t j = static_cast<size_t>(t); j < count; j += static_cast<size_t>(workers)) {
          scores[j] = distortion(u0_ + cone_ * green.col(static_cast<Eigen::Index>(j)));
        }
      });
      for (size_t j = 0; j < count; ++j) {
        const int p = todo[start + j];
        cache_[p] = scores[j];
        // The best vertex so far, first by score and then by index (sorted_scores' order).
        if (keep_best_column_ && (best_vertex_ < 0 || scores[j] < best_score_ ||
                                  (scores[j] == best_score_ && p < best_vertex_))) {
          best_vertex_ = p;
          best_score_ = scores[j];
          best_column_ = green.col(static_cast<Eigen::Index>(j));
        }
      }
    }
    std::vector<double> out;
    out.reserve(vertices.size());
    for (int p : vertices) out.push_back(cache_.at(p));
    return out;
  }

  // Keeps the Green column of the best-scored vertex, so that log_scale needs no solve there.
  void keep_best_column() { keep_best_column_ = true; }

  // The model's log scale factors for a cone at p: u0 + cone G_p (one back-substitution, none
  // for the kept best vertex's column).
  Eigen::VectorXd log_scale(int p) {
    if (p == best_vertex_ && best_column_.size() == n_) return u0_ + cone_ * best_column_;
    Eigen::MatrixXd rhs = base_rhs_ - Eigen::VectorXd::Constant(n_, cone_ / n_);
    rhs(p, 0) += cone_;
    solver_.solve_columns_in_place(rhs);
    ++solves_;
    return rhs.col(0);
  }

  double scored(int p) const { return cache_.count(p) ? cache_.at(p) : kInfinity; }
  int solves() const { return solves_; }
  LinearWork work() const { return solver_.work(); }
  const std::map<int, double>& cache() const { return cache_; }

 private:
  // Predicted area distortion of the log-scale field u: faces scale by exp(2 * mean u).
  // log(S/sum S) - log(s/sum s) = d - log(sum S) + log(sum S e^{-d}), normalised in log space.
  double distortion(const Eigen::VectorXd& u) const {
    const Eigen::Index F = faces_.rows();
    Eigen::ArrayXd d(F);
    for (Eigen::Index f = 0; f < F; ++f) {
      d[f] = -2.0 / 3.0 * (u[faces_(f, 0)] + u[faces_(f, 1)] + u[faces_(f, 2)]);
    }
    const Eigen::ArrayXd flat = log_area_.array() - d;
    const double peak = flat.maxCoeff();
    const double log_flat_total = peak + std::log((flat - peak).exp().sum());
    return (d - log_total_ + log_flat_total).square().mean();
  }

  int n_;
  SymmetricFactorization solver_;
  double cone_ = 0, log_total_ = 0;
  Eigen::VectorXd base_rhs_, u0_, log_area_;
  bool keep_best_column_ = false;
  int best_vertex_ = -1;
  double best_score_ = kInfinity;
  Eigen::VectorXd best_column_;  // G_p of best_vertex_
  Eigen::MatrixX3i faces_;
  std::map<int, double> cache_;
  int solves_ = 0;
};

std::vector<int> interior_vertices(const Mesh& mesh) {
  std::vector<int> pool;
  for (auto v : mesh.vertices()) {
    if (!mesh.is_boundary(v)) pool.push_back(v.idx());
  }
  return pool;
}

// The vertices' neighbours in OpenMesh's circulation order, in compressed rows: the sampling's
// breadth-first searches visit hundreds of thousands of vertices dozens of times, five times
// faster than through the circulators, in the same order.
struct VertexGraph {
  explicit VertexGraph(const Mesh& mesh) : offsets(mesh.n_vertices() + 1, 0) {
    neighbours.reserve(2 * mesh.n_edges());
    for (auto v : mesh.vertices()) {
      for (auto w : mesh.vv_range(v)) neighbours.push_back(w.idx());
      offsets[static_cast<size_t>(v.idx()) + 1] = static_cast<int>(neighbours.size());
    }
  }
  [[nodiscard]] int size() const { return static_cast<int>(offsets.size()) - 1; }
  template <class Visit>
  void for_neighbours(int v, const Visit& visit) const {
    for (int k = offsets[static_cast<size_t>(v)]; k < offsets[static_cast<size_t>(v) + 1]; ++k) {
      visit(neighbours[static_cast<size_t>(k)]);
    }
  }
  std::vector<int> offsets, neighbours;
};

// Ring distances from `source`, at most `limit` rings; -1 beyond. `rings[r]` lists the vertices
// at distance r in breadth-first order.
std::vector<std::vector<int>> rings_around(const VertexGraph& graph, int source, int limit) {
  std::vector<int> depth(static_cast<size_t>(graph.size()), -1);
  std::vector<std::vector<int>> rings{{source}};
  depth[static_cast<size_t>(source)] = 0;
  for (int r = 1; r <= limit; ++r) {
    std::vector<int> next;
    for (int v : rings.back()) {
      graph.for_neighbours(v, [&](int w) {
        if (depth[static_cast<size_t>(w)] >= 0) return;
        depth[static_cast<size_t>(w)] = r;
        next.push_back(w);
      });
    }
    if (next.empty()) break;
    rings.push_back(std::move(next));
  }
  return rings;
}

// Farthest-point sample of `count` interior vertices by ring distance, from the first one.
std::vector<int> spread_sample(const VertexGraph& graph, const std::vector<int>& pool, int count) {
  if (static_cast<int>(pool.size()) <= count) return pool;
  std::vector<int> distance(static_cast<size_t>(graph.size()), std::numeric_limits<int>::max());
  std::vector<int> sample;
  int next = pool.front();
  while (static_cast<int>(sample.size()) < count) {
    sample.push_back(next);
    // Breadth-first update of the distance to the sample, stopping where it does not improve.
    std::vector<int> frontier{next};
    distance[static_cast<size_t>(next)] = 0;
    while (!frontier.empty()) {
      std::vector<int> grown;
      for (int v : frontier) {
        graph.for_neighbours(v, [&](int w) {
          int& dw = distance[static_cast<size_t>(w)];
          if (dw <= distance[static_cast<size_t>(v)] + 1) return;
          dw = distance[static_cast<size_t>(v)] + 1;
          grown.push_back(w);
        });
      }
      frontier = std::move(grown);
    }
    int farthest = -1;
    for (int v : pool) {
      if (farthest < 0 || distance[static_cast<size_t>(v)] > distance[static_cast<size_t>(farthest)]) {
        farthest = v;
      }
    }
    if (distance[static_cast<size_t>(farthest)] == 0) break;
    next = farthest;
  }
  return sample;
}

// The linear model and its first spread sample of ranked_count interior vertices (all of them
// when there are no more): the sample's breadth-first searches do not need the model and run on
// a second thread while it is built. An empty pool is the caller's to refuse.
struct SampledModel {
  std::optional<LinearModel> model;
  std::optional<VertexGraph> graph;
  std::vector<int> pool, sample;
  int count = 0;  // the sample's size: ranked_count of the pool

  SampledModel(const Mesh& mesh, const SurfaceTopology& topology,
               const SingularityOptions& options);
};

int ranked_count(int interior, int vertices, const SingularityOptions& options) {
  const double budget = options.ranking_work / std::max(vertices, 1);
  const int count = static_cast<int>(std::clamp(budget, static_cast<double>(options.min_ranked_vertices),
                                                static_cast<double>(options.max_ranked_vertices)));
  return std::min(interior, count);
}

SampledModel::SampledModel(const Mesh& mesh, const SurfaceTopology& topology,
                           const SingularityOptions& options) {
  run_workers(2, [&](int t) {
    if (t == 0) {
      model.emplace(mesh, topology.euler_characteristic);
      return;
    }
    graph.emplace(mesh);
    pool = interior_vertices(mesh);
    count = ranked_count(static_cast<int>(pool.size()), static_cast<int>(mesh.n_vertices()),
                         options);
    sample = spread_sample(*graph, pool, count);
    if (options.beside_factorization) options.beside_factorization();
  });
}

// Zoom search on the linear model from `centre`: a farthest-point sample of the vertices
// within `radius` rings is scored (one blocked solve), the centre moves to the best of them,
// and the radius shrinks threefold, down to two rings (the real flows' one-ring descent, when
// the budget has flows, or the smoothness of the distortion in the cone's position takes over).
void zoom_search(const Mesh& mesh, const VertexGraph& graph, LinearModel& model, int centre,
                 int radius, int samples) {
  while (radius >= 2) {
    std::vector<int> ball;
    for (const auto& ring : rings_around(graph, centre, radius)) {
      for (int v : ring) {
        if (!mesh.is_boundary(mesh.vertex_handle(v))) ball.push_back(v);
      }
    }
    const std::vector<int> sample = spread_sample(graph, ball, samples);
    const std::vector<double> scores = model.score(sample);
    double best = model.scored(centre);
    for (size_t i = 0; i < sample.size(); ++i) {
      if (scores[i] < best) {
        best = scores[i];
        centre = sample[i];
      }
    }
    radius /= 3;
  }
}

std::vector<SingularityScore> sorted_scores(const std::map<int, double>& cache) {
  std::vector<SingularityScore> scores;
  scores.reserve(cache.size());
  for (const auto& [vertex, score] : cache) scores.push_back({vertex, score});
  std::stable_sort(scores.begin(), scores.end(), [](const SingularityScore& a, const SingularityScore& b) {
    return a.area_distortion < b.area_distortion;
  });
  return scores;
}

}  // namespace

std::vector<SingularityScore> rank_singularities(const Mesh& mesh, const SingularityOptions& options,
                                                 LinearWork* work) {
  SampledModel sampled(mesh, surface_topology(mesh), options);
  LinearModel& model = *sampled.model;
  (void)model.score(sampled.sample);
  if (work) *work += model.work();
  return sorted_scores(model.cache());
}

namespace {

// one_cone_area_distortion, adding the flow's linear work to `work`.
// `first_metric`: as solve_one_cone_flow's; `metric_position`, when given, receives the
// converged metric's metric_order_position (-1 when none converged or another metric did).
double flow_area_distortion(const Mesh& mesh, int vertex, const SingularityOptions& options,
                            LinearWork& work, int first_metric = 0,
                            int* metric_position = nullptr) {
  OneConeProblem problem = prepare_one_cone(mesh, vertex, options.valence, false);
  FlowResult result =
      solve_one_cone_flow(problem, options.flow, options.keep_metric, first_metric);
  work += result.linear_work;
  const bool converged = result.converged();
  if (metric_position) {
    *metric_position = converged && !options.keep_metric
                           ? metric_order_position(problem.kind, result.metric_name)
                           : -1;
  }
  if (!converged) return kInfinity;
  return measure_distortion(problem.mesh, result.lengths).area_distortion;
}

// Metrics of one_cone_metric_order the descents may skip: those before the earliest one that
// converged at the first batch's candidates, when every candidate converged on a metric of
// that order (0 otherwise). A metric that failed at all the best linear candidates (the
// inversive distance on a simplified genus-0 domain: two failed runs costing ~80% of each
// flow) is not tried again at their neighbours.
int metrics_to_skip(const std::vector<int>& positions) {
  if (positions.empty()) return 0;
  int skip = std::numeric_limits<int>::max();
  for (int p : positions) {
    if (p < 0) return 0;
    skip = std::min(skip, p);
  }
  return skip;
}

// The flows of the best `count` linear candidates (fewer when fewer are ranked), each on a
// problem of its own, on options.verification_threads threads: each writes its own slot and
// the slots are read in rank order, so the scores, the work and any exception (the first
// candidate's in rank order) are the serial loop's. The flows' progress reports are
// serialised.
std::vector<SingularityScore> verify_in_parallel(const Mesh& mesh,
                                                 const std::vector<SingularityScore>& ranked,
                                                 int count, const SingularityOptions& options,
                                                 LinearWork& work, std::vector<int>& positions) {
  const size_t n = static_cast<size_t>(std::clamp<int>(count, 0, static_cast<int>(ranked.size())));
  std::vector<SingularityScore> scores(n);
  std::vector<LinearWork> works(n);
  std::vector<std::exception_ptr> errors(n);
  positions.assign(n, -1);
  SingularityOptions each = options;
  std::mutex reporting;
  if (options.flow.progress) {
    each.flow.progress = [&](const FlowProgress& p) {
      const std::lock_guard<std::mutex> lock(reporting);
      options.flow.progress(p);
    };
  }
  const int workers =
      std::min(requested_threads(options.verification_threads), static_cast<int>(n));
  run_workers(workers, [&](int t) {
    for (size_t i = static_cast<size_t>(t); i < n; i += static_cast<size_t>(workers)) {
      try {
        scores[i] = {ranked[i].vertex, flow_area_distortion(mesh, ranked[i].vertex, each,
                                                            works[i], 0, &positions[i])};
      } catch (...) {
        errors[i] = std::current_exception();
      }
    }
  });
  for (size_t i = 0; i < n; ++i) {
    if (errors[i]) std::rethrow_exception(errors[i]);
    work += works[i];
  }
  return scores;
}

}  // namespace

double one_cone_area_distortion(const Mesh& mesh, int vertex, const SingularityOptions& options) {
  LinearWork work;
  return flow_area_distortion(mesh, vertex, options, work);
}

int zoom_sample_count(int vertices, const SingularityOptions& options) {
  const double share = 0.4 * options.ranking_work / std::max(vertices, 1);
  const double low = options.min_zoom_samples;
  const double high = std::max(options.min_zoom_samples, options.max_zoom_samples);
  return static_cast<int>(std::clamp(std::round(share), low, high));
}

int verified_count(int vertices, const SingularityOptions& options) {
  const double v = std::max(vertices, 1);
  return static_cast<int>(std::min<double>(options.max_verified_flows, std::floor(options.verification_work / (v * v))));
}

SingularityChoice choose_singularity(const Mesh& mesh, const SingularityOptions& options) {
  const Stopwatch start;
  SingularityChoice choice;
  const SurfaceTopology topology = surface_topology(mesh);
  if (!needs_singular_vertex(topology)) {
    choice.area_distortion = flow_area_distortion(mesh, -1, options, choice.linear_work);
    choice.flows_run = 1;
    choice.seconds = start.seconds();
    return choice;
  }
  // 1. The linear model on a spread sample, then zoom searches from the best few.
  const int vertices = static_cast<int>(mesh.n_vertices());
  SampledModel sampled(mesh, topology, options);
  LinearModel& model = *sampled.model;
  // The large meshes' choice is the model's best-scored vertex: its prediction is kept.
  if (options.predict_log_scale) model.keep_best_column();
  const std::vector<int>& pool = sampled.pool;
  if (pool.empty()) throw InvalidInputError("no interior vertex to put the singularity on");
  const int count = sampled.count;
  const VertexGraph& graph = *sampled.graph;
  (void)model.score(sampled.sample);
  if (count < static_cast<int>(pool.size())) {
    // Sample spacing in rings: count disks of radius r cover about count * 3 r^2 vertices.
    const int radius = std::max(
        2, static_cast<int>(std::sqrt(static_cast<double>(pool.size()) / (3.0 * count))) + 1);
    // Zoom searches from the best few sampled vertices, fewer as the mesh grows (each costs
    // about three blocked solves).
    const int starts = std::clamp(
        static_cast<int>(options.ranking_work / (static_cast<double>(vertices) * kBlockColumns)), 1,
        std::max(1, options.linear_search_starts));
    const std::vector<SingularityScore> sampled = sorted_scores(model.cache());
    for (int i = 0; i < std::min<int>(starts, static_cast<int>(sampled.size())); ++i) {
      zoom_search(mesh, graph, model, sampled[static_cast<size_t>(i)].vertex, radius,
                  zoom_sample_count(vertices, options));
    }
  }
  const std::vector<SingularityScore> ranked = sorted_scores(model.cache());
  choice.ranked = static_cast<int>(ranked.size());

  // 2. Real flows within the budget: the best linear candidates, then one-ring descents.
  int budget = verified_count(vertices, options);
  std::set<int> checked;
  std::vector<int> positions;
  for (const SingularityScore& s :
       verify_in_parallel(mesh, ranked, std::min(budget, options.verified_candidates), options,
                          choice.linear_work, positions)) {
    checked.insert(s.vertex);
    choice.verified.push_back(s);
    ++choice.flows_run;
    --budget;
  }
  const int skip = metrics_to_skip(positions);
  auto verify = [&](int v) {
    if (budget <= 0 || !checked.insert(v).second) return;
    choice.verified.push_back(
        {v, flow_area_distortion(mesh, v, options, choice.linear_work, skip)});
    ++choice.flows_run;
    --budget;
  };
  auto score_of = [&](int v) {
    for (const auto& s : choice.verified) {
      if (s.vertex == v) return s.area_distortion;
    }
    return kInfinity;
  };
  auto by_distortion = [](const SingularityScore& a, const SingularityScore& b) {
    return a.area_distortion < b.area_distortion;
  };
  if (options.refine_in_one_ring && !choice.verified.empty()) {
    // Greedy descent over one-rings from the best few verified vertices (the linear model
    // can misjudge a whole region, so one basin is not enough), each until its vertex beats
    // all its neighbours or the budget is spent.
    std::vector<SingularityScore> starts = choice.verified;
    std::sort(starts.begin(), starts.end(), by_distortion);
    starts.resize(std::min<size_t>(starts.size(), static_cast<size_t>(options.descent_starts)));
    for (const SingularityScore& s : starts) {
      if (!std::isfinite(s.area_distortion)) continue;
      int centre = s.vertex;
      for (int round = 0; round < 10 && budget > 0; ++round) {
        int next = centre;
        for (auto w : mesh.vv_range(mesh.vertex_handle(centre))) {
          if (mesh.is_boundary(w)) continue;
          verify(w.idx());
          if (score_of(w.idx()) < score_of(next)) next = w.idx();
        }
        if (next == centre) break;
        centre = next;
      }
    }
  }
  if (choice.verified.empty()) {
    // The linear model's choice, verified by the caller's own flow.
    choice.vertex = ranked.front().vertex;
    choice.area_distortion = std::numeric_limits<double>::quiet_NaN();
  } else {
    const SingularityScore best = *std::min_element(choice.verified.begin(), choice.verified.end(), by_distortion);
    if (!std::isfinite(best.area_distortion)) {
      throw SolverError(
          "no candidate singular vertex gave a converging flow; try valence options or another metric");
    }
    choice.vertex = best.vertex;
    choice.area_distortion = best.area_distortion;
  }
  choice.predicted_area_distortion = model.score({choice.vertex})[0];
  if (options.predict_log_scale) choice.predicted_log_scale = model.log_scale(choice.vertex);
  choice.linear_solves = model.solves();
  choice.linear_work += model.work();
  choice.seconds = start.seconds();
  return choice;
}

}  // namespace ricci
