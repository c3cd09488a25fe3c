#include "spline/surface/cap_holes.h"

#include <algorithm>
#include <optional>
#include <utility>

#include "ricci/mesh/errors.h"
#include "ricci/util/cancel.h"
#include "spline/fill/hole_fill.h"
#include "spline/fill/meet_patch.h"
#include "spline/fill/rims.h"

namespace spline {
namespace {

// The surface next to the rims moved to meet the patches (spline/fill/meet_patch.h), then the
// seams measured again; kept only when the largest seam drops (it is a least-squares compromise
// along the whole rim: where the seam is already small it can grow a little).
void move_surface_to_patches(SplineSurface& surface) {
  auto& fills = surface.fills;
  if (fills.empty()) return;
  ManifoldSpline moved = surface.spline;
  MeetPatchResult met = meet_patches(surface.spline, fills);
  moved.control_points = std::move(met.control_points);
  // The seams of the move, measured by meet_patches when it ranked its rounds.
  std::vector<SeamReport> seams = std::move(met.seams);
  if (seams.empty())
    for (const auto& fill : fills) seams.push_back(measure_seam(moved, fill));
  double before = 0.0, after = 0.0;
  for (std::size_t i = 0; i < fills.size(); ++i) {
    before = std::max(before, fills[i].max_normal_jump_deg);
    after = std::max(after, seams[i].max_normal_jump_deg);
  }
  if (!(after < before)) return;
  surface.spline = std::move(moved);
  for (std::size_t i = 0; i < fills.size(); ++i) {
    fills[i].max_normal_jump_deg = seams[i].max_normal_jump_deg;
    fills[i].edge_normal_jump_deg = seams[i].edge_normal_jump_deg;
    fills[i].max_position_gap = seams[i].max_position_gap;
    fills[i].rms_position_gap = seams[i].rms_position_gap;
  }
}

// The rims, and the cone hole's patch when one was made while choosing them.
struct ChosenRims {
  std::vector<Rim> rims;
  int cone = -1;  ///< index of the cone hole's rim, -1 without one
  std::optional<HoleFill> cone_fill;
};

int cone_rim(const std::vector<Rim>& rims) {
  for (std::size_t i = 0; i < rims.size(); ++i) {
    if (rims[i].kind == Rim::Kind::cone_hole) return static_cast<int>(i);
  }
  return -1;
}

// The cone hole grows past faces where the chart is badly conditioned or the spline folds
// (FindRimsOptions). A cone patch that still flips (a seam above 90 degrees: the patch folds
// where the rim turns too fast for it) is retried on the hole grown by one and then two more
// layers (within FindRimsOptions' caps), keeping the smallest seam (block.off at 2000 faces:
// 169 degrees, one more layer 2.4). A hole grown within its reach (ConeHoleLimits::reach_layers)
// is compared with the one the caps give, and the smaller seam kept: past a sliver band the rim
// comes clear, but a larger rim need not be met better (couplingdown, `msp fit --fold-rounds 0
// --refine-rounds 0`: seam 12.6 degrees on the hole reached, 6.4 on the capped one).
ChosenRims choose_rims(const SplineSurface& surface, const std::vector<char>& in_domain,
                       const CapHolesOptions& options, const RimMergeOptions& merge,
                       const FillOptions& final_options) {
  // The holes tried are compared by their patches on a uniform grid when the limits say so;
  // the chosen one alone gets the patch of final_options (below).
  FillOptions cone_options = final_options;
  const bool compare_uniform = options.cone_hole.compare_uniform && !options.screening;
  if (compare_uniform) cone_options.corner_refinement = 1;
  const std::vector<char>& collar_faces = options.collar_faces;
  const auto& space = *surface.spline.space;
  const std::vector<double> scale = chart_scale_by_face(space, surface.domain);
  const auto normal_step = [&surface](int face) {
    return max_normal_step_deg(surface.spline, face);
  };
  const auto find = [&](int extra_layers, const std::vector<int>& to_cover, bool reach) {
    FindRimsOptions rim_options;
    rim_options.extra_cone_layers = extra_layers;
    rim_options.cone_rim_vertices_to_cover = to_cover;
    rim_options.max_cone_layers = options.cone_hole.max_layers;
    rim_options.max_cone_cover_fraction = options.cone_hole.max_cover_fraction;
    rim_options.cone_margin_layers = options.cone_hole.margin_layers;
    if (reach) {
      rim_options.cone_reach_layers = options.cone_hole.reach_layers;
      rim_options.cone_reach_cover_fraction = options.cone_hole.reach_cover_fraction;
    }
    rim_options.boundary_faces = collar_faces;
    return find_rims(surface.domain, in_domain, space.atlas().in_domain, rim_options, merge,
                     scale, normal_step);
  };
  ChosenRims chosen;
  bool chosen_reach = options.cone_hole.reach_layers > 0;
  chosen.rims = find(0, {}, chosen_reach);
  chosen.cone = cone_rim(chosen.rims);
  if (chosen.cone < 0 || !options.make_patches) return chosen;
  chosen.cone_fill = fill_rim(surface.spline, surface.domain, chosen.rims[chosen.cone],
                              cone_options);
  constexpr double kFlipped = 90.0;
  int chosen_extra = 0;
  std::vector<int> covered_vertices;
  // Adopts the rims of find(extra, to_cover) when its cone patch's seam is smaller than the
  // chosen's. False when the cone hole would be the same (or there is none): nothing to try.
  const auto try_rims = [&](int extra, const std::vector<int>& to_cover, bool reach) {
    std::vector<Rim> rims = find(extra, to_cover, reach);
    const int cone = cone_rim(rims);
    if (cone < 0 || rims[cone].covered_faces == chosen.rims[chosen.cone].covered_faces)
      return false;
    HoleFill fill = fill_rim(surface.spline, surface.domain, rims[cone], cone_options);
    if (!(fill.max_normal_jump_deg < chosen.cone_fill->max_normal_jump_deg)) return true;
    chosen.rims = std::move(rims);
    chosen.cone = cone;
    chosen.cone_fill = std::move(fill);
    chosen_extra = extra;
    chosen_reach = reach;
    covered_vertices = to_cover;
    return true;
  };
  if (chosen_reach && !options.screening) (void)try_rims(0, {}, false);
  for (int extra = 1; extra <= 2 && chosen.cone_fill->max_normal_jump_deg > kFlipped; ++extra) {
    if (!try_rims(extra, {}, chosen_reach)) break;
  }
  // A seam missing its target at a few rim vertices (the fitted surface turns sharply at a
  // vertex, e.g. fertility's cone rim: 30 degrees at one vertex, below 6 elsewhere): the faces
  // around the ends of the worst rim edges join the hole, up to options.cone_hole.vertex_rounds
  // times, each kept only when the seam drops.
  const int vertex_rounds = options.screening ? 0 : options.cone_hole.vertex_rounds;
  for (int round = 0; round < vertex_rounds; ++round) {
    const HoleFill& fill = *chosen.cone_fill;
    if (!(fill.max_normal_jump_deg > cone_options.target_jump_deg) ||
        fill.max_normal_jump_deg > kFlipped)
      break;
    const Rim& rim = chosen.rims[chosen.cone];
    const std::vector<int> vertices = rim_vertices(rim, surface.domain);
    const double worst = std::max(cone_options.target_jump_deg, 0.25 * fill.max_normal_jump_deg);
    std::vector<int> to_cover = covered_vertices;
    const std::size_t m = vertices.size();
    for (std::size_t j = 0; j < m && j < fill.edge_normal_jump_deg.size(); ++j) {
      if (!(fill.edge_normal_jump_deg[j] > worst)) continue;
      to_cover.push_back(vertices[j]);
      to_cover.push_back(vertices[(j + 1) % m]);
    }
    std::sort(to_cover.begin(), to_cover.end());
    to_cover.erase(std::unique(to_cover.begin(), to_cover.end()), to_cover.end());
    const double before = chosen.cone_fill->max_normal_jump_deg;
    if (!try_rims(chosen_extra, to_cover, chosen_reach) ||
        !(chosen.cone_fill->max_normal_jump_deg < before))
      break;
  }
  if (compare_uniform && final_options.corner_refinement > 1) {
    HoleFill refined =
        fill_rim(surface.spline, surface.domain, chosen.rims[chosen.cone], final_options);
    if (refined.max_normal_jump_deg < chosen.cone_fill->max_normal_jump_deg)
      chosen.cone_fill = std::move(refined);
  }
  return chosen;
}

FillOptions fill_options_for(bool input_boundary, const CapHolesOptions& options) {
  FillOptions fill_options;
  if (options.screening) fill_options.corner_refinement = 1;
  fill_options.cancel = options.cancel;
  // The punctured sphere's hole is a cone hole in all but name: filled like one (its
  // projection may fold; the patch is laid out on a circle either way). Without the
  // fallback its fold left the only rim of camel.off and knight_decimated.off open.
  fill_options.require_simple_projection = input_boundary;
  // Boundary loops the caller asked to cap are capped too when no height field fits them
  // (most of them, e.g. beetle.off's merged ones): watertight, not G1, counted in
  // fallback_fills.
  fill_options.fallback_boundary = true;
  return fill_options;
}

}  // namespace

ConeHoleLimits cone_hole_limits(int genus, bool fairing_free_cone) {
  ConeHoleLimits limits;
  if (genus >= 4) {
    limits.max_layers = 8;
    limits.max_cover_fraction = 0.25;
    limits.vertex_rounds = 2;
  }
  if (genus >= 8) {
    limits.reach_layers = 12;
    limits.reach_cover_fraction = 0.5;
    limits.margin_layers = 1;
    limits.compare_uniform = true;
  }
  if (fairing_free_cone) limits.reach_layers = 0;
  return limits;
}

bool retries_cone_hole(const ConeHoleLimits& limits) {
  return limits.vertex_rounds > 0 || limits.reach_layers > 0;
}

CapHolesReport cap_holes(SplineSurface& surface, const CapHolesOptions& options) {
  const auto& space = *surface.spline.space;
  const int faces = static_cast<int>(surface.domain.n_faces());
  std::vector<char> in_domain(static_cast<std::size_t>(faces), 0);
  for (int f = 0; f < faces; ++f) in_domain[static_cast<std::size_t>(f)] = space.in_domain(f);
  surface.skipped_faces.assign(in_domain.size(), 0);
  const std::vector<char>& collar = options.collar_faces;
  if (!collar.empty() && collar.size() != in_domain.size()) {
    throw ricci::InvalidInputError("cap_holes: " + std::to_string(collar.size()) +
                                   " collar flags for " + std::to_string(faces) + " faces");
  }
  for (std::size_t f = 0; f < in_domain.size(); ++f) {
    surface.skipped_faces[f] = !in_domain[f] || (!collar.empty() && collar[f]);
  }
  // Nearby boundary loops merge into one hole only when they will be capped: left open, every
  // input loop keeps its own rim, so the surface keeps the input's boundary loops.
  RimMergeOptions merge;
  merge.boundary_loops = options.fill_boundaries || !options.open_input;
  ChosenRims chosen = choose_rims(surface, in_domain, options, merge,
                                  fill_options_for(false, options));
  CapHolesReport report;
  surface.fills.clear();
  surface.open_rims.clear();
  if (!options.make_patches) {
    for (Rim& rim : chosen.rims) {
      const bool input_boundary = rim.kind == Rim::Kind::boundary && options.open_input;
      report.boundary_rims += input_boundary;
      // As below: an open boundary's band stays with a collar, a capped rim's faces go.
      if (!input_boundary || options.fill_boundaries || collar.empty())
        for (int f : rim.covered_faces) surface.skipped_faces[static_cast<std::size_t>(f)] = 1;
      surface.open_rims.push_back(std::move(rim));
    }
    return report;
  }
  for (std::size_t r = 0; r < chosen.rims.size(); ++r) {
    Rim& rim = chosen.rims[r];
    // A closed input's domain boundary is the punctured sphere's removed star: always capped.
    const bool input_boundary = rim.kind == Rim::Kind::boundary && options.open_input;
    if (input_boundary) ++report.boundary_rims;
    // An open rim's band is kept with a collar (the spline is a partition of unity up to the
    // boundary there) and skipped without one: the spline collapses in that band (holes.off
    // with the band kept: fit max 27% of the diagonal, 1.8% without it).
    if (input_boundary && !options.fill_boundaries) {
      if (collar.empty()) {
        for (int f : rim.covered_faces) surface.skipped_faces[static_cast<std::size_t>(f)] = 1;
      }
      surface.open_rims.push_back(std::move(rim));
      continue;
    }
    for (int f : rim.covered_faces) surface.skipped_faces[static_cast<std::size_t>(f)] = 1;
    try {
      surface.fills.push_back(static_cast<int>(r) == chosen.cone
                                  ? std::move(*chosen.cone_fill)
                                  : fill_rim(surface.spline, surface.domain, rim,
                                             fill_options_for(input_boundary, options)));
      if (!surface.fills.back().g1) ++report.fallback_fills;
    } catch (const ricci::InvalidInputError& e) {
      // A boundary whose projection folds cannot be capped: left open and reported.
      report.failures.push_back(std::string(rim_kind_description(rim.kind)) + ": " + e.what());
      surface.open_rims.push_back(std::move(rim));
    }
  }
  ricci::throw_if_cancelled(options.cancel, "cap_holes");
  move_surface_to_patches(surface);
  for (const auto& fill : surface.fills) {
    report.max_normal_jump_deg = std::max(report.max_normal_jump_deg, fill.max_normal_jump_deg);
    report.max_position_gap = std::max(report.max_position_gap, fill.max_position_gap);
  }
  return report;
}

}  // namespace spline
