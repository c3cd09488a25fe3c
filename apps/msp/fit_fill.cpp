#include "msp/fit_fill.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include <ricci/mesh/errors.h>

#include <spline/fill/hole_fill.h>
#include <spline/fill/meet_patch.h>
#include <spline/fill/rims.h>
#include <spline/tessellate/tessellate_fill.h>

namespace msp {

struct FitFills {
  std::vector<spline::Rim> rims;
  std::vector<spline::HoleFill> fills;
  std::vector<spline::PatchTessellation> patches;  ///< By fill, at the tessellation's density.
};

namespace {

const char* rim_kind_name(spline::Rim::Kind kind) {
  switch (kind) {
    case spline::Rim::Kind::cone_hole:
      return "cone hole";
    case spline::Rim::Kind::boundary:
      return "boundary";
    case spline::Rim::Kind::excluded:
      return "excluded faces";
  }
  return "rim";
}

double distance_to_patch(const spline::HoleFill& fill, const spline::PatchTessellation& patch,
                         const Eigen::Vector3d& target, int iterations) {
  if (patch.positions.rows() == 0) return -1.0;
  Eigen::Index nearest = 0;
  (patch.positions.rowwise() - target.transpose()).rowwise().squaredNorm().minCoeff(&nearest);
  Eigen::Vector2d u = patch.parameters.row(nearest).transpose();
  spline::PatchPoint p = fill.evaluate(u);
  double best = (p.position - target).norm();
  double radius = 0.0;
  for (const auto& c : fill.corners) radius = std::max(radius, (c - fill.center).norm());
  for (int it = 0; it < iterations; ++it) {
    Eigen::Matrix<double, 3, 2> j;
    j << p.du, p.dv;
    const Eigen::Matrix2d jtj = j.transpose() * j;
    if (!(std::abs(jtj.determinant()) > 1e-300)) break;
    const Eigen::Vector2d next = u - jtj.ldlt().solve(j.transpose() * (p.position - target));
    // Beyond D: the closest point is on the spline, which is measured there.
    if ((next - fill.center).norm() > radius) break;
    const spline::PatchPoint trial = fill.evaluate(next);
    const double d = (trial.position - target).norm();
    if (!(d < best)) break;
    best = d;
    u = next;
    p = trial;
  }
  return best;
}

// The surface next to the rims moved to meet the patches (spline/fill/meet_patch.h), then the
// seams measured again; kept only when the largest seam drops (it is a least-squares compromise
// along the whole rim: where the seam is already small it can grow a little, horse.off 0.43 ->
// 0.48 degrees, cup.off 2.4 -> 2.5). Measured (`msp fit` defaults): the largest seam normal
// jump 4.2 -> 1.3 degrees on bunny_npm_closed.off, 3.5 -> 1.2 camel.off, 1.6 -> 0.92
// armadillo.obj, 6.9 -> 4.2 femur.off, 6.1 -> 2.7 genus3.off, 0.92 -> 0.69 bunny_igl.off; the
// fit RMS changes by < 1% of itself.
void move_surface_to_patches(FitRun& run, std::vector<spline::HoleFill>& fills) {
  if (fills.empty()) return;
  spline::ManifoldSpline moved = run.scan.spline;
  moved.control_points = spline::meet_patches(run.scan.spline, fills).control_points;
  std::vector<spline::SeamReport> seams;
  double before = 0.0, after = 0.0;
  for (const auto& fill : fills) {
    seams.push_back(spline::measure_seam(moved, fill));
    before = std::max(before, fill.max_normal_jump_deg);
    after = std::max(after, seams.back().max_normal_jump_deg);
  }
  if (!(after < before)) return;
  run.scan.spline = std::move(moved);
  run.fill_normal_jump_deg = 0.0;
  run.fill_position_gap = 0.0;
  for (std::size_t i = 0; i < fills.size(); ++i) {
    auto& fill = fills[i];
    fill.max_normal_jump_deg = seams[i].max_normal_jump_deg;
    fill.max_position_gap = seams[i].max_position_gap;
    fill.rms_position_gap = seams[i].rms_position_gap;
    run.fill_normal_jump_deg = std::max(run.fill_normal_jump_deg, fill.max_normal_jump_deg);
    run.fill_position_gap = std::max(run.fill_position_gap, fill.max_position_gap);
  }
}

// The rims, and the cone hole's patch when one was made while choosing them.
struct ChosenRims {
  std::vector<spline::Rim> rims;
  int cone = -1;  ///< index of the cone hole's rim, -1 without one
  std::optional<spline::HoleFill> cone_fill;
};

// The cone hole grows past faces where the chart is badly conditioned or the spline folds
// (FindRimsOptions). A cone patch that still flips (a seam above 90 degrees: the patch folds
// where the rim turns too fast for it) is retried on the hole grown by one and then two more
// layers (within FindRimsOptions' caps), keeping the smallest seam. Measured (msp-bench fill
// --faces 2000, then meet_patches): block.off 169 degrees, one more layer 2.4.
ChosenRims choose_rims(const FitRun& run, const ricci::Mesh& domain,
                       const std::vector<char>& in_domain, const spline::RimMergeOptions& merge,
                       const spline::FillOptions& cone_options) {
  const auto& space = *run.scan.spline.space;
  const std::vector<double> scale = spline::chart_scale_by_face(space, domain);
  const auto normal_step = [&run](int face) {
    return spline::max_normal_step_deg(run.scan.spline, face);
  };
  const auto find = [&](int extra_layers) {
    spline::FindRimsOptions rim_options;
    rim_options.extra_cone_layers = extra_layers;
    rim_options.boundary_faces = run.scan.collar_faces;
    return spline::find_rims(domain, in_domain, space.atlas().in_domain, rim_options, merge,
                             scale, normal_step);
  };
  const auto cone_of = [](const std::vector<spline::Rim>& rims) {
    for (std::size_t i = 0; i < rims.size(); ++i) {
      if (rims[i].kind == spline::Rim::Kind::cone_hole) return static_cast<int>(i);
    }
    return -1;
  };
  ChosenRims chosen;
  chosen.rims = find(0);
  chosen.cone = cone_of(chosen.rims);
  if (chosen.cone < 0) return chosen;
  chosen.cone_fill =
      spline::fill_rim(run.scan.spline, domain, chosen.rims[chosen.cone], cone_options);
  constexpr double kFlipped = 90.0;
  for (int extra = 1; extra <= 2 && chosen.cone_fill->max_normal_jump_deg > kFlipped; ++extra) {
    std::vector<spline::Rim> rims = find(extra);
    const int cone = cone_of(rims);
    if (cone < 0 || rims[cone].covered_faces == chosen.rims[chosen.cone].covered_faces) break;
    spline::HoleFill fill = spline::fill_rim(run.scan.spline, domain, rims[cone], cone_options);
    if (fill.max_normal_jump_deg < chosen.cone_fill->max_normal_jump_deg) {
      chosen.rims = std::move(rims);
      chosen.cone = cone;
      chosen.cone_fill = std::move(fill);
    }
  }
  return chosen;
}

spline::FillOptions fill_options_for(bool input_boundary) {
  spline::FillOptions fill_options;
  // The punctured sphere's hole is a cone hole in all but name: filled like one (its
  // projection may fold; the patch is laid out on a circle either way). Without the
  // fallback its fold left the only rim of camel.off and knight_decimated.off open.
  fill_options.require_simple_projection = input_boundary;
  // Boundary loops the user asked to cap are capped too when no height field fits them
  // (most of them, e.g. beetle.off's merged ones): watertight, not G1, counted in
  // fallback_fills.
  fill_options.fallback_boundary = true;
  return fill_options;
}

}  // namespace

std::vector<char> fill_rims(FitRun& run, const ricci::Mesh& domain, const FitRunOptions& options) {
  const auto& space = *run.scan.spline.space;
  auto fills = std::make_shared<FitFills>();
  // The boundary collar's ghost faces are fitted but are not the surface: skipped, and the
  // rims run along the surface's own boundary.
  const std::vector<char>& collar = run.scan.collar_faces;
  const auto ghost = [&collar](int f) {
    return !collar.empty() && collar[static_cast<std::size_t>(f)] != 0;
  };
  std::vector<char> skip(domain.n_faces(), 0);
  for (int f = 0; f < static_cast<int>(domain.n_faces()); ++f)
    skip[static_cast<std::size_t>(f)] = !space.in_domain(f) || ghost(f);
  // Nearby boundary loops merge into one hole only when they will be capped: left open, every
  // input loop keeps its own rim, so the surface keeps the input's boundary loops.
  std::vector<char> in_domain(domain.n_faces(), 0);
  for (int f = 0; f < static_cast<int>(domain.n_faces()); ++f) in_domain[f] = space.in_domain(f);
  spline::RimMergeOptions merge;
  merge.boundary_loops = options.fill_boundaries || run.input.boundary_loops == 0;
  ChosenRims chosen = choose_rims(run, domain, in_domain, merge, fill_options_for(false));
  fills->rims = std::move(chosen.rims);
  for (std::size_t r = 0; r < fills->rims.size(); ++r) {
    const spline::Rim& rim = fills->rims[r];
    // Skipped even when the rim stays open: the spline collapses in that band (open/holes.off
    // with the band kept: fit max 27% of the diagonal, 1.8% without it). With
    // --fill-boundaries, growing merges boundary loops a ring or two apart into one hole (a
    // disk: spline/fill/rims.h), so there can be fewer rims than loops (beetle.off: 11, 4).
    // A closed input's domain boundary is the punctured sphere's removed star: always capped.
    const bool input_boundary =
        rim.kind == spline::Rim::Kind::boundary && run.input.boundary_loops > 0;
    if (input_boundary) ++run.boundary_rims;
    if (input_boundary && !options.fill_boundaries) {
      ++run.open_rims;
      // With the collar the spline is a partition of unity up to the boundary: kept.
      if (collar.empty()) {
        for (int f : rim.covered_faces) skip[static_cast<std::size_t>(f)] = 1;
      }
      continue;
    }
    for (int f : rim.covered_faces) skip[static_cast<std::size_t>(f)] = 1;
    try {
      fills->fills.push_back(static_cast<int>(r) == chosen.cone
                                 ? *chosen.cone_fill
                                 : spline::fill_rim(run.scan.spline, domain, rim,
                                                    fill_options_for(input_boundary)));
      const auto& fill = fills->fills.back();
      if (!fill.g1) ++run.fallback_fills;
      run.fill_normal_jump_deg = std::max(run.fill_normal_jump_deg, fill.max_normal_jump_deg);
      run.fill_position_gap = std::max(run.fill_position_gap, fill.max_position_gap);
    } catch (const ricci::InvalidInputError& e) {
      // A boundary whose projection folds cannot be capped: left open and reported.
      run.fill_failures.push_back(std::string(rim_kind_name(rim.kind)) + ": " + e.what());
      ++run.open_rims;
    }
  }
  move_surface_to_patches(run, fills->fills);
  run.filled_rims = static_cast<int>(fills->fills.size());
  run.fills = fills;
  return skip;
}

void append_fills(FitRun& run) {
  if (!run.fills) return;
  auto& f = *run.fills;
  f.patches.clear();
  for (std::size_t i = 0; i < f.fills.size(); ++i) {
    f.patches.push_back(spline::tessellate_fill(f.fills[i], run.tessellation.density));
    spline::append_fill(run.tessellation, f.fills[i], f.patches.back(), static_cast<int>(i));
  }
}

double distance_to_fills(const FitRun& run, const Eigen::Vector3d& target, int iterations) {
  double best = -1.0;
  if (!run.fills) return best;
  for (std::size_t i = 0; i < run.fills->patches.size(); ++i) {
    const double d =
        distance_to_patch(run.fills->fills[i], run.fills->patches[i], target, iterations);
    if (d >= 0 && (best < 0 || d < best)) best = d;
  }
  return best;
}

}  // namespace msp
