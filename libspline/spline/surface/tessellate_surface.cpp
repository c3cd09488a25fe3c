#include "spline/surface/tessellate_surface.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <unordered_map>

#include "ricci/mesh/errors.h"
#include "spline/tessellate/tessellate_fill.h"

namespace spline {
namespace {

// A patch welds to the spline's samples of its rim edges: their faces must be tessellated.
void check_rims_tessellated(const Tessellation& t, const SplineSurface& surface) {
  for (std::size_t i = 0; i < surface.fills.size(); ++i) {
    for (const RimEdge& e : surface.fills[i].rim.edges) {
      const bool known = e.face >= 0 && e.face < static_cast<int>(surface.domain.n_faces());
      if (known && t.tessellated(e.face)) continue;
      throw ricci::InvalidInputError("tessellate_surface: fill " + std::to_string(i) +
                                     " has a rim edge on face " + std::to_string(e.face) +
                                     ", which is not tessellated");
    }
  }
}

}  // namespace

int default_density(int domain_faces) {
  const double d = std::sqrt(120000.0 / std::max(1, domain_faces));
  return std::clamp(static_cast<int>(std::lround(d)), 2, 8);
}

Tessellation tessellate_surface(const SplineSurface& surface, const TessellationOptions& options,
                                std::vector<PatchTessellation>& patches) {
  TessellationOptions spline_options = options;
  spline_options.skip_faces = surface.skipped_faces;
  Tessellation t = tessellate(surface.spline, surface.domain, spline_options);
  check_rims_tessellated(t, surface);
  patches.clear();
  patches.reserve(surface.fills.size());
  for (std::size_t i = 0; i < surface.fills.size(); ++i) {
    patches.push_back(tessellate_fill(surface.fills[i], t.density));
    append_fill(t, surface.fills[i], patches.back(), static_cast<int>(i));
  }
  if (options.refine_levels > 0)
    refine_sharp_turns(t, surface.spline, options.refine_turn_deg, options.refine_levels,
                       options.threads);
  return t;
}

Tessellation tessellate_surface(const SplineSurface& surface, const TessellationOptions& options) {
  std::vector<PatchTessellation> patches;
  return tessellate_surface(surface, options, patches);
}

TriangleSoup float_welded(const Tessellation& t) {
  struct Key {
    float x, y, z;
    bool operator==(const Key& o) const { return x == o.x && y == o.y && z == o.z; }
  };
  struct Hash {
    std::size_t operator()(const Key& k) const {
      std::uint32_t b[3];
      std::memcpy(b, &k, sizeof b);
      return (std::size_t{b[0]} * 0x9E3779B1u) ^ (std::size_t{b[1]} * 0x85EBCA77u) ^ b[2];
    }
  };
  std::unordered_map<Key, int, Hash> index;
  std::vector<int> welded(static_cast<std::size_t>(t.positions.rows()));
  std::vector<Key> keys;
  for (Eigen::Index i = 0; i < t.positions.rows(); ++i) {
    const Key k{static_cast<float>(t.positions(i, 0)), static_cast<float>(t.positions(i, 1)),
                static_cast<float>(t.positions(i, 2))};
    auto [it, inserted] = index.emplace(k, static_cast<int>(keys.size()));
    if (inserted) keys.push_back(k);
    welded[static_cast<std::size_t>(i)] = it->second;
  }
  TriangleSoup soup;
  soup.positions.resize(static_cast<Eigen::Index>(keys.size()), 3);
  for (std::size_t i = 0; i < keys.size(); ++i)
    soup.positions.row(static_cast<Eigen::Index>(i)) << keys[i].x, keys[i].y, keys[i].z;
  soup.triangles.reserve(t.triangles.size());
  for (const auto& tri : t.triangles)
    soup.triangles.push_back({welded[static_cast<std::size_t>(tri[0])],
                              welded[static_cast<std::size_t>(tri[1])],
                              welded[static_cast<std::size_t>(tri[2])]});
  return soup;
}

WatertightReport float_welded_topology(const Tessellation& t) {
  const TriangleSoup soup = float_welded(t);
  return check_watertight(soup.triangles, soup.positions);
}

}  // namespace spline
