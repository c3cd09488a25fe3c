// index_modules: grouping by topology, distance matrices and nearest neighbours.
#include <gtest/gtest.h>

#include <ricci/analysis/module_index.h>
#include <ricci/mesh/errors.h>

namespace ricci {
namespace {

ModuleResult module(ModuleKind kind, int boundaries, std::vector<double> values) {
  ModuleResult m;
  m.kind = kind;
  m.boundary_loops = boundaries;
  m.values = std::move(values);
  return m;
}

TEST(ModuleIndex, GroupsByTopologyAndOrdersNeighbours) {
  const std::vector<ModuleResult> modules = {
      module(ModuleKind::Annulus, 2, {0.10}), module(ModuleKind::Hyperbolic, 3, {3, 2, 1}),
      module(ModuleKind::Annulus, 2, {0.40}), module(ModuleKind::Annulus, 2, {0.15}),
      module(ModuleKind::Hyperbolic, 4, {3, 2, 1, 1})};
  const std::vector<ModuleGroup> groups = index_modules(modules);
  ASSERT_EQ(groups.size(), 3u);
  EXPECT_EQ(groups[0].members, (std::vector<int>{0, 2, 3}));
  EXPECT_EQ(groups[1].members, (std::vector<int>{1}));
  EXPECT_EQ(groups[2].members, (std::vector<int>{4}));
  EXPECT_NEAR(groups[0].distances(0, 1), 0.30, 1e-15);
  EXPECT_NEAR(groups[0].distances(2, 1), 0.25, 1e-15);
  EXPECT_EQ(groups[0].distances, groups[0].distances.transpose());
  EXPECT_EQ(groups[0].nearest[0], (std::vector<int>{2, 1}));
  EXPECT_EQ(groups[0].nearest[1], (std::vector<int>{2, 0}));
  EXPECT_TRUE(groups[1].nearest[0].empty());
}

TEST(ModuleIndex, SameTopologyDifferentLengthsThrows) {
  const std::vector<ModuleResult> modules = {module(ModuleKind::Annulus, 2, {0.1}),
                                             module(ModuleKind::Annulus, 2, {0.1, 0.2})};
  EXPECT_THROW((void)index_modules(modules), InvalidInputError);
}

}  // namespace
}  // namespace ricci
