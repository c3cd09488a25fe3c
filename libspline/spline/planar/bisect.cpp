#include "spline/planar/bisect.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "ricci/mesh/errors.h"
#include "ricci/util/edge_key.h"

namespace spline {
namespace {

class Bisector {
 public:
  explicit Bisector(PlanarTriangulation& t) : t_(t) {
    Eigen::Vector2d lo = t_.positions[0], hi = lo;
    for (const auto& p : t_.positions) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    unit_ = 1e-12 * (hi - lo).squaredNorm();
    const std::vector<Eigen::Vector3i> initial = std::move(t_.triangles);
    t_.triangles.clear();
    for (const auto& tri : initial) add(tri);
  }

  [[nodiscard]] int triangle_count() const { return alive_count_; }
  [[nodiscard]] int slots() const { return static_cast<int>(t_.triangles.size()); }
  [[nodiscard]] bool alive(int f) const { return alive_[f] != 0; }

  [[nodiscard]] double longest_length(int f) const {
    const int k = longest_corner(f);
    const auto& v = t_.triangles[f];
    return (t_.positions[v[(k + 1) % 3]] - t_.positions[v[(k + 2) % 3]]).norm();
  }
  [[nodiscard]] Eigen::Vector2d centroid(int f) const {
    const auto& v = t_.triangles[f];
    return (t_.positions[v[0]] + t_.positions[v[1]] + t_.positions[v[2]]) / 3.0;
  }

  // Splits f at its longest edge, first splitting the neighbours along the path of longest
  // edges (each strictly longer in the (length, key) order, so the path ends).
  void split(int f) {
    std::vector<int> path{f};
    while (!path.empty()) {
      const int g = path.back();
      if (!alive(g)) {
        path.pop_back();
        continue;
      }
      const std::uint64_t e = longest_key(g);
      const int n = across(e, g);
      if (n < 0 || longest_key(n) == e) {
        split_pair(g, n, e);
        path.pop_back();
      } else {
        path.push_back(n);
      }
    }
  }

  void compact() {
    std::vector<Eigen::Vector3i> kept;
    kept.reserve(static_cast<std::size_t>(alive_count_));
    for (std::size_t f = 0; f < t_.triangles.size(); ++f) {
      if (alive_[f]) kept.push_back(t_.triangles[f]);
    }
    t_.triangles = std::move(kept);
  }

 private:
  // The corner opposite the longest edge. Squared lengths are compared in units of 1e-12 of
  // the squared box diagonal, ties (the two halves of a split edge) by the edge key: a strict
  // order of the edges, the same for a scaled or moved copy (rounding would otherwise break
  // the halves' tie differently and refine the copy otherwise).
  [[nodiscard]] int longest_corner(int f) const {
    const auto& v = t_.triangles[f];
    int best = 0;
    long long best_length = -1;
    std::uint64_t best_key = 0;
    for (int k = 0; k < 3; ++k) {
      const int a = v[(k + 1) % 3], b = v[(k + 2) % 3];
      const long long length =
          std::llround((t_.positions[a] - t_.positions[b]).squaredNorm() / unit_);
      const std::uint64_t key = ricci::undirected_edge_key(a, b);
      if (length > best_length || (length == best_length && key < best_key)) {
        best = k;
        best_length = length;
        best_key = key;
      }
    }
    return best;
  }
  [[nodiscard]] std::uint64_t longest_key(int f) const {
    const int k = longest_corner(f);
    const auto& v = t_.triangles[f];
    return ricci::undirected_edge_key(v[(k + 1) % 3], v[(k + 2) % 3]);
  }
  [[nodiscard]] int across(std::uint64_t e, int f) const {
    const auto it = faces_.find(e);
    if (it == faces_.end()) return -1;
    return it->second[0] == f ? it->second[1] : it->second[0];
  }

  void add(const Eigen::Vector3i& tri) {
    const int f = static_cast<int>(t_.triangles.size());
    t_.triangles.push_back(tri);
    alive_.push_back(1);
    ++alive_count_;
    for (int k = 0; k < 3; ++k) {
      auto [it, inserted] = faces_.try_emplace(ricci::undirected_edge_key(tri[k], tri[(k + 1) % 3]),
                                               std::array<int, 2>{f, -1});
      if (!inserted) it->second[it->second[0] < 0 ? 0 : 1] = f;
    }
  }
  void remove(int f) {
    alive_[f] = 0;
    --alive_count_;
    const auto& tri = t_.triangles[f];
    for (int k = 0; k < 3; ++k) {
      auto it = faces_.find(ricci::undirected_edge_key(tri[k], tri[(k + 1) % 3]));
      if (it->second[0] == f) it->second[0] = -1;
      if (it->second[1] == f) it->second[1] = -1;
      if (it->second[0] < 0 && it->second[1] < 0) faces_.erase(it);
    }
  }

  // Splits f (and n, the face across edge e, when there is one) at e's midpoint.
  void split_pair(int f, int n, std::uint64_t e) {
    const int a = static_cast<int>(e >> 32), b = static_cast<int>(e & 0xffffffffu);
    const int m = static_cast<int>(t_.positions.size());
    t_.positions.push_back(0.5 * (t_.positions[a] + t_.positions[b]));
    for (int g : {f, n}) {
      if (g < 0) continue;
      const Eigen::Vector3i v = t_.triangles[g];
      int k = 0;
      while (v[k] == a || v[k] == b) ++k;  // the corner opposite e
      remove(g);
      add({v[k], v[(k + 1) % 3], m});
      add({v[k], m, v[(k + 2) % 3]});
    }
  }

  PlanarTriangulation& t_;
  double unit_ = 1.0;
  std::vector<char> alive_;
  int alive_count_ = 0;
  std::unordered_map<std::uint64_t, std::array<int, 2>> faces_;
};

}  // namespace

void refine_to_size(PlanarTriangulation& triangulation,
                    const std::function<double(const Eigen::Vector2d&)>& size,
                    int max_triangles) {
  validate(triangulation);
  if (triangulation.triangles.empty()) return;
  Bisector bisector(triangulation);
  for (bool changed = true; changed && bisector.triangle_count() < max_triangles;) {
    changed = false;
    for (int f = 0; f < bisector.slots() && bisector.triangle_count() < max_triangles; ++f) {
      if (!bisector.alive(f)) continue;
      const double target = size(bisector.centroid(f));
      if (!(target > 0.0) || !std::isfinite(target)) {
        throw ricci::InvalidInputError("refine_to_size: the size function gave " +
                                       std::to_string(target));
      }
      if (bisector.longest_length(f) > target) {
        bisector.split(f);
        changed = true;
      }
    }
  }
  bisector.compact();
}

}  // namespace spline
