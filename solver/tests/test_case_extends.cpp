// Case files that extend others: key-by-key merging, lists replaced as a whole, chains,
// cycles, and errors naming the file where the offending key was set.

#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

#include "io/case_config.hpp"
#include "test_case_support.hpp"

namespace hfdda::io {
namespace {

using namespace case_test;

TEST(CaseFileExtends, ChildOverridesKeyByKey) {
  const CaseConfig c = load_case_file(kCases + "extends_child.yaml");
  EXPECT_EQ(c.file, kCases + "extends_child.yaml");
  EXPECT_EQ(c.title, "child");
  EXPECT_EQ(c.mesh.cell_size_m, 0.5);                   // overridden
  EXPECT_EQ(c.mesh.split, mesh::CellSplit::four);       // kept from the base
  ASSERT_TRUE(c.domain.inner.has_value());              // kept from the base
  EXPECT_EQ(c.domain.inner->xmax, 18);
  EXPECT_EQ(c.time.dt_s, 1);                            // kept
  EXPECT_EQ(c.time.end_time_s, 10);                     // overridden
  ASSERT_EQ(c.materials.size(), 2u);                    // list not in child: kept
  EXPECT_EQ(c.materials[1].name, "outer_rock");
  EXPECT_EQ(c.materials[1].line, 9);                    // line in the base file
  EXPECT_EQ(c.mesh_file, kCases + "extends_child.yaml");  // last file writing `mesh`
  EXPECT_EQ(c.mesh.line, 3);
}

TEST(CaseFileExtends, ListsAreReplacedAsAWhole) {
  const CaseConfig c = load_case_file(kCases + "extends_child.yaml");
  ASSERT_EQ(c.fractures.size(), 1u);
  EXPECT_EQ(c.fractures[0].name, "c");
  EXPECT_EQ(c.fractures[0].from, Vec2(-4, 0));
  EXPECT_EQ(c.fractures[0].pressure_Pa, std::optional<double>(1e6));
  EXPECT_EQ(c.fractures[0].line, 5);  // line in the child file
}

TEST(CaseFileExtends, ChainOfThreeFromAnotherFolder) {
  const CaseConfig c = load_case_file(kCases + "derived/extends_grandchild.yaml");
  EXPECT_EQ(c.title, "grandchild");
  EXPECT_EQ(c.mesh.cell_size_m, 0.5);              // from the child
  EXPECT_EQ(c.mesh.split, mesh::CellSplit::four);  // from the base
  EXPECT_FALSE(c.domain.inner.has_value());        // null removes the inherited one
  ASSERT_EQ(c.materials.size(), 1u);
  EXPECT_EQ(c.materials[0].name, "only");
  EXPECT_EQ(c.materials[0].youngs_modulus_Pa, 5e9);
  ASSERT_EQ(c.fractures.size(), 1u);
  EXPECT_EQ(c.fractures[0].name, "c");
}

TEST(CaseFileExtends, ErrorNamesTheFileOfTheBadKey) {
  expect_error(error_of_file(kCases + "extends_bad_child.yaml"),
               kCases + "extends_bad_base.yaml", 2, "mesh.cel_size", "unknown key");
}

TEST(CaseFileExtends, MergedCheckNamesTheFileWhereTheKeyWasSet) {
  // The child shrinks the domain; fracture 'a' is written in the base, line 11.
  expect_error(error_of_file(kCases + "extends_shrink.yaml"), kCases + "extends_base.yaml", 11,
               "fractures[0].from", "lies outside the domain");
}

TEST(CaseFileExtends, CycleIsAnError) {
  expect_error(error_of_file(kCases + "cycle_a.yaml"), kCases + "cycle_b.yaml", 2, "extends",
               "cycle");
  expect_error(error_of_file(kCases + "cycle_self.yaml"), kCases + "cycle_self.yaml", 1,
               "extends", "cycle");
}

TEST(CaseFileExtends, MissingBaseIsReportedAtTheExtendsLine) {
  const std::string label = kCases + "not_written.yaml";
  expect_error(error_of_text("title: x\nextends: no_such_base.yaml\n", label), label, 2,
               "extends", "cannot be read");
}

TEST(CaseFileExtends, RelativeToTheLabelDirectory) {
  const CaseConfig c = load_case_text("extends: extends_base.yaml\n", kCases + "virtual.yaml");
  EXPECT_EQ(c.title, "base");
  EXPECT_EQ(c.file, kCases + "virtual.yaml");
}

}  // namespace
}  // namespace hfdda::io
