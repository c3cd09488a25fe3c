#include "ricci/hyperbolic/universal_cover.h"

#include <map>
#include <tuple>

namespace ricci {
namespace {

/// Bucket key of a map (sign-normalised entries rounded to a coarse grid) so duplicates are
/// found by looking at a few neighbours instead of every element.
std::tuple<long, long, long, long> bucket(const Mobius& g, double cell) {
  Eigen::Matrix2cd m = g.m;
  const Complex a = m(0, 0);
  if (a.real() < 0 || (a.real() == 0 && a.imag() < 0)) m = -m;
  return {std::lround(m(0, 0).real() / cell), std::lround(m(0, 0).imag() / cell),
          std::lround(m(0, 1).real() / cell), std::lround(m(0, 1).imag() / cell)};
}

}  // namespace

std::vector<GroupElement> group_elements(const std::vector<Mobius>& generators, int max_length,
                                         double tolerance, int max_elements,
                                         const std::function<bool(const Mobius&)>& keep) {
  std::vector<Mobius> letters;
  for (const Mobius& g : generators) {
    letters.push_back(g);
    letters.push_back(g.inverse());
  }
  std::vector<GroupElement> elements{{Mobius::identity(), 0}};
  std::multimap<std::tuple<long, long, long, long>, int> index;
  const double cell = 1e-4;
  auto known = [&](const Mobius& g) {
    // Rounding splits near-equal maps across at most neighbouring cells: check the 3^4 cells.
    const auto [a, b, c, d] = bucket(g, cell);
    for (long i = -1; i <= 1; ++i)
      for (long j = -1; j <= 1; ++j)
        for (long k = -1; k <= 1; ++k)
          for (long l = -1; l <= 1; ++l) {
            auto range = index.equal_range({a + i, b + j, c + k, d + l});
            for (auto it = range.first; it != range.second; ++it) {
              if (mobius_distance(elements[it->second].map, g) < tolerance) return true;
            }
          }
    return false;
  };
  index.insert({bucket(elements[0].map, cell), 0});
  size_t begin = 0;
  for (int length = 1; length <= max_length; ++length) {
    const size_t end = elements.size();
    for (size_t i = begin; i < end; ++i) {
      for (const Mobius& letter : letters) {
        const Mobius g = elements[i].map * letter;
        if (known(g) || (keep && !keep(g))) continue;
        index.insert({bucket(g, cell), static_cast<int>(elements.size())});
        elements.push_back({g, length});
        if (static_cast<int>(elements.size()) >= max_elements) return elements;
      }
    }
    begin = end;
  }
  return elements;
}

}  // namespace ricci
