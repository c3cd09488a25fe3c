// Projections onto a manifold spline and the parameter correction built on them (fit.h).
#include <Eigen/Cholesky>
#include <array>
#include <cmath>
#include <string>
#include <utility>

#include "ricci/mesh/errors.h"
#include "spline/fit/correction.h"
#include "spline/fit/fit.h"
#include "spline/tessellate/parallel_for.h"

namespace spline {
namespace {

// True when the point lies on an edge of the domain's rim (an edge whose other face is missing
// or outside the domain): a projection clamped there is over the hole (or beyond an open
// boundary), which the spline does not cover (correct_parameters keeps the old parameter).
bool on_domain_rim(const ManifoldSplineSpace& space, int face, const Eigen::Vector3d& bary) {
  for (int k = 0; k < 3; ++k) {
    const int g = space.neighbour(face, k);
    if ((g < 0 || !space.in_domain(g)) && bary[k] <= 1e-12) return true;
  }
  return false;
}

// ManifoldSpline::evaluate (the same checks and sums, so the same bits) keeping the samples.
SurfaceJet evaluate_keeping(const ManifoldSpline& spline, const DomainPoint& point,
                            BasisDerivatives derivatives,
                            std::vector<ManifoldBasisSample>& samples) {
  const ManifoldSplineSpace& space = *spline.space;
  if (point.face < 0 || point.face >= space.face_count() || !space.in_domain(point.face)) {
    throw ricci::InvalidInputError("project_to_spline: face " + std::to_string(point.face) +
                                   " is not in the spline's domain");
  }
  const int chart = space.chart_of(point.face);
  space.evaluate_basis_at(chart, point.face,
                          space.chart_point(chart, point.face, point.barycentric), {},
                          derivatives, samples);
  return combine(samples, spline.control_points, chart, derivatives);
}

// The kept samples (values and gradients) of point k as evaluate_keeping would give them.
void take_samples(const detail::PointBasisValues& kept, std::size_t k,
                  std::vector<ManifoldBasisSample>& samples) {
  const auto block = static_cast<std::size_t>(kept.block[k]);
  const std::vector<int>& function = kept.function[block];
  const std::vector<double>& value = kept.value[block];
  const std::vector<Eigen::Vector2d>& gradient = kept.gradient[block];
  samples.resize(static_cast<std::size_t>(kept.count[k]));
  for (int i = 0; i < kept.count[k]; ++i) {
    const int e = kept.first[k] + i;
    ManifoldBasisSample& s = samples[static_cast<std::size_t>(i)];
    s.function = function[e];
    s.jet.value = value[e];
    s.jet.gradient = gradient[e];
    s.jet.hessian.setZero();
  }
}

// project_to_spline; `current` ends with the basis samples at the returned point, `trial` is
// scratch. With start_known, `current` holds the start's samples (values and gradients) already.
Projection project_keeping(const ManifoldSpline& spline, const DomainPoint& start,
                           const Eigen::Vector3d& target, int iterations, bool start_known,
                           std::vector<ManifoldBasisSample>& current,
                           std::vector<ManifoldBasisSample>& trial) {
  const ManifoldSplineSpace& space = *spline.space;
  if (spline.control_points.rows() != space.function_count()) {
    throw ricci::InvalidInputError("manifold spline: " +
                                   std::to_string(spline.control_points.rows()) +
                                   " control points for " +
                                   std::to_string(space.function_count()) + " functions");
  }
  DomainPoint point = start;
  // Gauss-Newton needs positions and first derivatives; the last trial, if it is accepted, only
  // its position (the same bits as the full jet's).
  SurfaceJet jet =
      start_known
          ? combine(current, spline.control_points, space.chart_of(point.face),
                    BasisDerivatives::first)
          : evaluate_keeping(spline, point, BasisDerivatives::first, current);
  for (int it = 0; it < iterations; ++it) {
    const int chart = space.chart_of(point.face);
    Eigen::Matrix<double, 3, 2> j;
    j << jet.du, jet.dv;
    const Eigen::Matrix2d jtj = j.transpose() * j;
    if (std::abs(jtj.determinant()) < 1e-300) break;
    const Eigen::Vector2d step = -jtj.ldlt().solve(j.transpose() * (jet.position - target));
    const Eigen::Vector2d u = space.chart_point(chart, point.face, point.barycentric) + step;
    // The face of the neighbourhood (glued in this chart) containing u, else stay on the rim.
    DomainPoint next{-1, Eigen::Vector3d::Zero()};
    const ricci::Chart& c = space.atlas().charts[chart];
    // The face and the faces across its edges: one Gauss-Newton step rarely goes further.
    std::array<int, 4> candidates{point.face, -1, -1, -1};
    int candidate_count = 1;
    for (int a = 0; a < 3; ++a) {
      const int g = space.neighbour(point.face, a);
      if (g >= 0) candidates[candidate_count++] = g;
    }
    double best = -1e300;
    for (int i = 0; i < candidate_count; ++i) {
      const int g = candidates[i];
      if (!space.in_domain(g) || c.slot(g) < 0) continue;
      const Eigen::Vector3d bary = barycentric_in(space.atlas().face_positions(chart, g), u);
      const double worst = bary.minCoeff();
      if (worst > best) {
        best = worst;
        next = {g, bary};
      }
    }
    if (next.face < 0) break;
    if (best < 0.0) {  // outside the reachable faces: clamp into the best one
      next.barycentric = next.barycentric.cwiseMax(0.0);
      next.barycentric /= next.barycentric.sum();
    }
    const SurfaceJet trial_jet = evaluate_keeping(
        spline, next, it + 1 < iterations ? BasisDerivatives::first : BasisDerivatives::none,
        trial);
    if ((trial_jet.position - target).squaredNorm() > (jet.position - target).squaredNorm()) break;
    point = next;
    jet = trial_jet;
    std::swap(current, trial);
    if (step.norm() < 1e-12 * space.atlas().domain_diameter) break;
  }
  return {point, jet.position, (jet.position - target).norm()};
}

}  // namespace

Projection project_to_spline(const ManifoldSpline& spline, const DomainPoint& start,
                             const Eigen::Vector3d& target, int iterations) {
  // Per-thread samples: projections run point by point in hot loops.
  thread_local std::vector<ManifoldBasisSample> current, trial;
  return project_keeping(spline, start, target, iterations, false, current, trial);
}

FitErrors fit_errors(const ManifoldSpline& spline, const std::vector<DomainPoint>& parameters,
                     const Eigen::MatrixX3d& points, int iterations, int threads) {
  const auto count = static_cast<int>(parameters.size());
  Eigen::VectorXd distance = Eigen::VectorXd::Constant(count, -1.0);  // -1: skipped
  parallel_for(static_cast<std::size_t>(count), std::max(1, threads), [&](std::size_t i) {
    const auto k = static_cast<int>(i);
    if (parameters[i].face < 0 || !spline.space->in_domain(parameters[i].face)) return;
    const Eigen::Vector3d p = points.row(k).transpose();
    distance[k] = project_to_spline(spline, parameters[i], p, iterations).distance;
  });
  FitErrors errors;
  double sum = 0.0;
  for (int k = 0; k < count; ++k) {
    if (distance[k] < 0.0) continue;
    sum += distance[k] * distance[k];
    errors.max = std::max(errors.max, distance[k]);
    ++errors.points;
  }
  if (errors.points > 0) errors.rms = std::sqrt(sum / errors.points);
  return errors;
}

namespace detail {

CorrectedParameters correct_parameters_keeping(const ManifoldSpline& spline,
                                               const std::vector<DomainPoint>& parameters,
                                               const Eigen::MatrixX3d& points, int iterations,
                                               int threads, const PointBasisValues* start,
                                               PointBasisValues* kept) {
  if (static_cast<Eigen::Index>(parameters.size()) != points.rows()) {
    throw ricci::InvalidInputError("correct_parameters: " + std::to_string(parameters.size()) +
                                   " parameters for " + std::to_string(points.rows()) + " points");
  }
  const ManifoldSplineSpace& space = *spline.space;
  CorrectedParameters result;
  result.parameters = parameters;
  const auto count = static_cast<int>(parameters.size());
  std::vector<char> moved(parameters.size(), 0);
  constexpr std::size_t kBlock = 64;  // parallel_for's blocks: each kept block one thread's
  if (kept) {
    const std::size_t blocks = (parameters.size() + kBlock - 1) / kBlock;
    *kept = PointBasisValues{};
    kept->at.assign(parameters.size(), DomainPoint{-1, Eigen::Vector3d::Zero()});
    kept->block.resize(parameters.size());
    for (std::size_t k = 0; k < parameters.size(); ++k)
      kept->block[k] = static_cast<int>(k / kBlock);
    kept->first.assign(parameters.size(), 0);
    kept->count.assign(parameters.size(), 0);
    kept->function.assign(blocks, {});
    kept->value.assign(blocks, {});
  }
  // The samples at the point's kept parameter (the start, or the projection's end).
  const auto keep = [&](std::size_t k, const DomainPoint& at,
                        const std::vector<ManifoldBasisSample>& samples) {
    std::vector<int>& function = kept->function[k / kBlock];
    std::vector<double>& value = kept->value[k / kBlock];
    kept->at[k] = at;
    kept->first[k] = static_cast<int>(function.size());
    kept->count[k] = static_cast<int>(samples.size());
    for (const ManifoldBasisSample& s : samples) {
      function.push_back(s.function);
      value.push_back(s.jet.value);
    }
  };
  parallel_for(
      static_cast<std::size_t>(count), std::max(1, threads),
      [&](std::size_t k) {
        const DomainPoint& from = parameters[k];
        if (from.face < 0 || !space.in_domain(from.face)) return;
        thread_local std::vector<ManifoldBasisSample> current, trial;
        const bool known = start && start->holds_gradients(k, from);
        if (known) take_samples(*start, k, current);
        const Projection p =
            project_keeping(spline, from, points.row(static_cast<Eigen::Index>(k)).transpose(),
                            iterations, known, current, trial);
        const bool same = p.point.face == from.face && p.point.barycentric == from.barycentric;
        if (same || on_domain_rim(space, p.point.face, p.point.barycentric)) {
          if (kept && same) keep(k, from, current);
          return;
        }
        result.parameters[k] = p.point;
        moved[k] = 1;
        if (kept) keep(k, p.point, current);
      },
      kBlock);
  for (char m : moved) result.moved += m;
  return result;
}

}  // namespace detail

CorrectedParameters correct_parameters(const ManifoldSpline& spline,
                                       const std::vector<DomainPoint>& parameters,
                                       const Eigen::MatrixX3d& points, int iterations,
                                       int threads) {
  return detail::correct_parameters_keeping(spline, parameters, points, iterations, threads,
                                            nullptr, nullptr);
}

}  // namespace spline
