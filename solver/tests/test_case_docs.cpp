// The key reference docs/case_file.md, generated from the key tables.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "io/case_config.hpp"

namespace hfdda::io {
namespace {

/// On a mismatch the generated text is written into the build tree (never the source
/// tree or the working directory), to be copied over docs/case_file.md.
TEST(CaseFileDocs, MatchesGeneratedReference) {
  const std::string path = std::string(HFDDA_TEST_DATA_DIR) + "/../../../docs/case_file.md";
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  const std::string generated = case_file_reference_markdown();
  if (text.str() != generated) {
    const std::filesystem::path output =
        std::filesystem::path(HFDDA_TEST_OUTPUT_DIR) / "case_file.md.generated";
    std::ofstream(output) << generated;
    FAIL() << "docs/case_file.md differs from case_file_reference_markdown(); the generated "
              "text is in "
           << output.string() << ": copy it to " << path;
  }
}

TEST(CaseFileDocs, ReferenceNamesEveryKeyOfTheExampleFile) {
  const std::string reference = case_file_reference_markdown();
  for (const char* key :
       {"`extends`", "`outer`", "`inner`", "`cell_size`", "`outer_growth`", "`split`",
        "`max_area_inner`", "`max_area_outer`", "`min_angle`", "`region`", "`box`",
        "`youngs_modulus`", "`poissons_ratio`", "`density`", "`tensile_strength`",
        "`cohesion`", "`friction_angle`", "`breakable`", "`segment_length`",
        "`initially_open`", "`natural`", "`pressure`", "`sides`", "`at`", "`force`",
        "`body_force`", "`fixed_points`", "`method`", "`normal_stiffness`",
        "`vertex_vertex_activation`", "`fixed_point_stiffness`", "`analysis`",
        "`alm_tolerance`", "`tie_tolerance`", "`shear_failure_of_intact_joints`", "`dt`",
        "`end_time`", "`every_steps`", "`vtu`"})
    EXPECT_NE(reference.find(key), std::string::npos) << key;
}

TEST(CaseFileDocs, ReferenceNamesEveryFluidKey) {
  const std::string reference = case_file_reference_markdown();
  for (const char* key :
       {"## `fluid`", "## `injections[]` items", "## `probes[]` items", "`fluid_filled`",
        "`initial_width`", "`initial_pressure`", "`bulk_modulus`", "`viscosity`", "`reference_pressure`",
        "`leak_off_coefficient`", "`mass_rate`", "`start_time`", "`min_width_main`",
        "`min_width_tip`", "`max_closing_fraction`", "`coupling_tolerance`",
        "`max_coupling_iterations`", "`max_step_cuts`", "erratum 4 in docs/seed_errata.md",
        "`numerics.min_width_tip` <= `numerics.min_width_main`"})
    EXPECT_NE(reference.find(key), std::string::npos) << key;
}

}  // namespace
}  // namespace hfdda::io
