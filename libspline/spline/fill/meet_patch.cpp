// meet_patches: the surface next to the rims moved to meet the patches (meet_patch.h).
#include "spline/fill/meet_patch.h"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <iterator>
#include <string>
#include <unordered_map>
#include <utility>

#include "ricci/mesh/errors.h"
#include "spline/fill/patch_domain.h"
#include "spline/tessellate/parallel_for.h"

namespace spline {
namespace {

// The basis at a rim sample, evaluated like fill_detail::sample_rim: in the face's chart, the
// tie broken towards the kept face.
std::vector<ManifoldBasisSample> rim_basis(const ManifoldSplineSpace& space, const RimEdge& edge,
                                           double t) {
  const fill_detail::RimChartEdge in_chart = fill_detail::rim_chart_edge(space, edge);
  return space.evaluate_basis({edge.face, rim_edge_barycentric(edge, t)}, in_chart.chart,
                              in_chart.tie);
}

// One rim sample: the basis there, the surface's derivatives and the patch's normal.
struct Sample {
  std::vector<ManifoldBasisSample> basis;
  Eigen::Vector3d derivative[2];
  Eigen::Vector3d patch_normal;
};

// Per filled rim (fills' order) and rim edge: the parameters its rows sample.
using EdgeParameters = std::vector<std::vector<std::vector<double>>>;

std::vector<Sample> rim_samples(const ManifoldSpline& spline, const std::vector<HoleFill>& fills,
                                const EdgeParameters& parameters) {
  struct At {
    const HoleFill* fill;
    int edge;
    double t;
  };
  std::vector<At> where;
  for (std::size_t i = 0; i < fills.size(); ++i) {
    const HoleFill& fill = fills[i];
    if (!fill.g1) continue;  // a positions-only patch has no normals worth meeting
    for (int j = 0; j < static_cast<int>(fill.rim.edges.size()); ++j)
      for (const double t : parameters[i][static_cast<std::size_t>(j)])
        where.push_back({&fill, j, t});
  }
  // Evaluated in parallel, each into its own slot; kept in order.
  std::vector<Sample> all(where.size());
  parallel_for(where.size(), 0, [&](std::size_t k) {
    const At& at = where[k];
    const RimEdge& edge = at.fill->rim.edges[static_cast<std::size_t>(at.edge)];
    Sample& s = all[k];
    s.basis = rim_basis(*spline.space, edge, at.t);
    const SurfaceJet jet =
        combine(s.basis, spline.control_points, spline.space->chart_of(edge.face));
    s.derivative[0] = jet.du;
    s.derivative[1] = jet.dv;
    s.patch_normal = at.fill->evaluate(at.fill->parameter(at.edge, at.t)).normal;
  });
  std::vector<Sample> samples;
  samples.reserve(all.size());
  for (Sample& s : all)
    if (!s.patch_normal.isZero()) samples.push_back(std::move(s));
  return samples;
}

double mean_rim_edge_length(const ManifoldSpline& spline, const std::vector<HoleFill>& fills) {
  double sum = 0.0;
  int count = 0;
  for (const HoleFill& fill : fills) {
    for (const RimEdge& e : fill.rim.edges) {
      const Eigen::Vector3d a = spline.evaluate({e.face, rim_edge_barycentric(e, 0.0)}).position;
      const Eigen::Vector3d b = spline.evaluate({e.face, rim_edge_barycentric(e, 1.0)}).position;
      sum += (b - a).norm();
      ++count;
    }
  }
  return count > 0 && sum > 0.0 ? sum / count : 1.0;
}

// The moved functions (unknown k: function functions[k]) and the direction each moves along:
// the patch normals where it is non-zero, weighted by its value.
struct Moved {
  std::vector<int> functions;
  std::unordered_map<int, int> unknown;
  std::vector<Eigen::Vector3d> direction;
};

Moved moved_functions(const std::vector<Sample>& samples) {
  Moved moved;
  for (const Sample& s : samples) {
    for (const auto& b : s.basis) {
      const auto [it, added] =
          moved.unknown.try_emplace(b.function, static_cast<int>(moved.functions.size()));
      if (added) {
        moved.functions.push_back(b.function);
        moved.direction.emplace_back(Eigen::Vector3d::Zero());
      }
      moved.direction[it->second] += std::abs(b.jet.value) * s.patch_normal;
    }
  }
  for (auto& d : moved.direction) {
    if (d.norm() > 0.0) d.normalize();
  }
  return moved;
}

// The least-squares move for rows at `parameters` (meet_patch.h).
MeetPatchResult solve_meet(const ManifoldSpline& spline, const std::vector<HoleFill>& fills,
                           const EdgeParameters& parameters, const MeetPatchOptions& options) {
  MeetPatchResult result;
  result.control_points = spline.control_points;
  const std::vector<Sample> samples = rim_samples(spline, fills, parameters);
  const Moved moved = moved_functions(samples);
  const int unknowns = static_cast<int>(moved.functions.size());
  if (unknowns == 0) return result;
  const double h = mean_rim_edge_length(spline, fills);
  std::vector<Eigen::Triplet<double>> entries;
  std::vector<double> targets;
  for (const Sample& s : samples) {
    for (int d = 0; d < 2; ++d) {
      const double length = s.derivative[d].norm();
      if (!(length > 0.0)) continue;
      const auto row = static_cast<int>(targets.size());
      for (const auto& b : s.basis) {
        const int k = moved.unknown.at(b.function);
        entries.emplace_back(
            row, k, s.patch_normal.dot(moved.direction[k]) * b.jet.gradient[d] / length);
      }
      targets.push_back(-s.patch_normal.dot(s.derivative[d]) / length);
    }
    // The rim stays where the patch is welded to it (its normal offset is what could move).
    const auto row = static_cast<int>(targets.size());
    for (const auto& b : s.basis) {
      const int k = moved.unknown.at(b.function);
      entries.emplace_back(row, k, options.position_weight * b.jet.value *
                                        s.patch_normal.dot(moved.direction[k]) / h);
    }
    targets.push_back(0.0);
  }
  for (int k = 0; k < unknowns; ++k) {
    entries.emplace_back(static_cast<int>(targets.size()), k, options.change_weight / h);
    targets.push_back(0.0);
  }
  Eigen::SparseMatrix<double> a(static_cast<Eigen::Index>(targets.size()), unknowns);
  a.setFromTriplets(entries.begin(), entries.end());
  const Eigen::VectorXd b = Eigen::Map<const Eigen::VectorXd>(targets.data(), a.rows());
  const Eigen::SparseMatrix<double> normal = a.transpose() * a;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(normal);
  if (solver.info() != Eigen::Success)
    throw ricci::SolverError("meet_patches: the normal equations cannot be factorised");
  const Eigen::VectorXd rhs = a.transpose() * b;
  Eigen::VectorXd change = solver.solve(rhs);
  change += solver.solve(rhs - normal * change);  // one refinement step: the weights span 1e3
  if (!change.allFinite())
    throw ricci::SolverError("meet_patches: the solve produced non-finite control points");
  for (int k = 0; k < unknowns; ++k) {
    result.control_points.row(moved.functions[k]) += change[k] * moved.direction[k].transpose();
    result.max_change = std::max(result.max_change, std::abs(change[k]) / h);
  }
  result.moved_functions = unknowns;
  return result;
}

// measure_seam of every fill on `spline`.
std::vector<SeamReport> measure_seams(const ManifoldSpline& spline,
                                      const std::vector<HoleFill>& fills) {
  std::vector<SeamReport> seams;
  for (const HoleFill& fill : fills) seams.push_back(measure_seam(spline, fill));
  return seams;
}

// The largest seam of the G1 patches (the ones the rows meet).
double largest_seam(const std::vector<SeamReport>& seams, const std::vector<HoleFill>& fills) {
  double worst = 0.0;
  for (std::size_t i = 0; i < fills.size(); ++i)
    if (fills[i].g1) worst = std::max(worst, seams[i].max_normal_jump_deg);
  return worst;
}

}  // namespace

MeetPatchResult meet_patches(const ManifoldSpline& spline, const std::vector<HoleFill>& fills,
                             const MeetPatchOptions& options) {
  if (options.samples_per_edge < 1 || !(options.position_weight >= 0.0) ||
      !(options.change_weight > 0.0) || options.peak_rounds < 0) {
    throw ricci::InvalidInputError(
        "meet_patches: options out of range (samples_per_edge >= 1, position_weight >= 0, "
        "change_weight > 0, peak_rounds >= 0)");
  }
  const std::vector<double> fixed = fill_detail::rim_edge_parameters(options.samples_per_edge);
  EdgeParameters parameters;
  for (const HoleFill& fill : fills)
    parameters.emplace_back(fill.rim.edges.size(), fixed);
  MeetPatchResult best = solve_meet(spline, fills, parameters, options);
  if (options.peak_rounds == 0) return best;
  ManifoldSpline moved = spline;
  moved.control_points = best.control_points;
  best.seams = measure_seams(moved, fills);
  double best_seam = largest_seam(best.seams, fills);
  std::vector<std::pair<std::size_t, int>> edges;  // (fill, rim edge) of the G1 patches
  for (std::size_t i = 0; i < fills.size(); ++i) {
    if (!fills[i].g1) continue;
    for (int j = 0; j < static_cast<int>(fills[i].rim.edges.size()); ++j) edges.emplace_back(i, j);
  }
  for (int round = 0; round < options.peak_rounds; ++round) {
    // Rows also where the moved surface's seam peaks between them (the rim edges in parallel).
    parallel_for(
        edges.size(), 0,
        [&](std::size_t e) {
          const auto [i, j] = edges[e];
          std::vector<double>& t = parameters[i][static_cast<std::size_t>(j)];
          const std::vector<double> more =
              fill_detail::seam_parameters(moved, fills[i], j, options.samples_per_edge);
          std::vector<double> merged;
          std::merge(t.begin(), t.end(), more.begin(), more.end(), std::back_inserter(merged));
          merged.erase(std::unique(merged.begin(), merged.end()), merged.end());
          t = std::move(merged);
        },
        1);
    MeetPatchResult next = solve_meet(spline, fills, parameters, options);
    moved.control_points = next.control_points;
    next.seams = measure_seams(moved, fills);
    const double seam = largest_seam(next.seams, fills);
    if (seam < best_seam) {
      best = std::move(next);
      best_seam = seam;
    }
  }
  return best;
}

}  // namespace spline
