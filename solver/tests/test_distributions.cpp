// Parameters given as distributions (docs/distributions.md; W. E. Morgan, PhD
// dissertation, Georgia Institute of Technology, 2014, sections 5.5 and 5.6): each law's
// draws against a CDF written here from its definition (Kolmogorov-Smirnov), truncation
// bounds, reproducibility from the seed, the rules of the laws and of the case-file keys,
// and a case with distributions built (per run, per block and per joint draws) and run.

#include <gsl/gsl_rng.h>
#include <gtest/gtest.h>

#include "statistics_support.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include "io/case_config.hpp"
#include "simulation/model.hpp"
#include "simulation/run.hpp"
#include "simulation/snapshots.hpp"
#include "stochastic/scalar_distribution.hpp"
#include "test_case_support.hpp"

namespace hfdda::stochastic {
namespace {

using test::ks_critical;
using test::ks_statistic;

// The CDFs of the laws, written from their definitions (not the library's).
double triangular_cdf(double x, double a, double c, double b) {
  if (x <= a) return 0.0;
  if (x >= b) return 1.0;
  return x <= c ? (x - a) * (x - a) / ((b - a) * (c - a)) : 1.0 - (b - x) * (b - x) / ((b - a) * (b - c));
}
double normal_lower(double z) { return 0.5 * std::erfc(-z / std::numbers::sqrt2); }  // P(Z <= z)
double normal_upper(double z) { return 0.5 * std::erfc(z / std::numbers::sqrt2); }   // P(Z > z)
/// N(mean, sd^2) restricted to [lo, hi]; the upper tail through P(Z > z) for its digits.
double truncated_normal_cdf(double x, double mean, double sd, double lo, double hi) {
  if (x <= lo) return 0.0;
  if (x >= hi) return 1.0;
  const double a = (lo - mean) / sd, b = (hi - mean) / sd, z = (x - mean) / sd;
  if (a > 0) return (normal_upper(a) - normal_upper(z)) / (normal_upper(a) - normal_upper(b));
  return (normal_lower(z) - normal_lower(a)) / (normal_lower(b) - normal_lower(a));
}

struct LawCase {
  const char* name;
  ScalarDistribution law;
  std::function<double(double)> cdf;
};

std::vector<LawCase> law_cases() {
  return {
      {"uniform", ScalarDistribution::uniform(2, 5), [](double x) { return std::clamp((x - 2) / 3, 0.0, 1.0); }},
      // Table 5.5: E triangular 8, 10, 12 GPa.
      {"triangular", ScalarDistribution::triangular(8e9, 10e9, 12e9),
       [](double x) { return triangular_cdf(x, 8e9, 10e9, 12e9); }},
      {"triangular, mode at min", ScalarDistribution::triangular(25, 25, 35),
       [](double x) { return triangular_cdf(x, 25, 25, 35); }},
      // Table 5.5: natural-fracture width 80, 100, 200 um, triangular on log10.
      {"log_triangular", ScalarDistribution::log_triangular(80e-6, 100e-6, 200e-6),
       [](double x) {
         return x <= 0 ? 0.0 : triangular_cdf(std::log10(x), std::log10(80e-6), std::log10(100e-6), std::log10(200e-6));
       }},
      {"truncated_normal", ScalarDistribution::truncated_normal(30, 5, 25, 40),
       [](double x) { return truncated_normal_cdf(x, 30, 5, 25, 40); }},
      {"truncated_normal, upper tail", ScalarDistribution::truncated_normal(0, 1, 3, 6),
       [](double x) { return truncated_normal_cdf(x, 0, 1, 3, 6); }},
      {"truncated_normal, lower tail", ScalarDistribution::truncated_normal(10, 2, -1, 2),
       [](double x) { return truncated_normal_cdf(x, 10, 2, -1, 2); }},
      {"truncated_lognormal", ScalarDistribution::truncated_lognormal(1e-3, 0.8, 5e-4, 5e-3),
       [](double x) {
         return x <= 0 ? 0.0 : truncated_normal_cdf(std::log(x), std::log(1e-3), 0.8, std::log(5e-4), std::log(5e-3));
       }},
  };
}

TEST(ScalarDistribution, DrawsFollowTheirCdf) {
  // 20000 draws per law and seed against the CDF written above; the library's own CDF
  // is checked against it too.
  for (const LawCase& c : law_cases()) {
    SCOPED_TRACE(c.name);
    ASSERT_FALSE(c.law.validate().has_value()) << c.law.validate()->rule;
    for (const std::uint64_t seed : {1u, 2u}) {
      const RandomStream stream(seed, c.name);
      std::vector<double> draws(20000);
      for (double& x : draws) x = c.law.sample(stream.get());
      const double d = ks_statistic(draws, c.cdf);
      EXPECT_LT(d, ks_critical(draws.size())) << "seed " << seed;
    }
    const double lo = c.law.lowest(), hi = c.law.highest();
    for (int i = -10; i <= 110; ++i) {
      const double x = lo + (hi - lo) * i / 100.0;
      EXPECT_NEAR(c.law.cdf(x), c.cdf(x), 1e-12) << "x = " << x;
    }
  }
}

TEST(ScalarDistribution, DrawsStayWithinTheirBounds) {
  // Truncations far into a tail and laws spanning decades: every draw in [min, max], and
  // spread over it.
  const std::vector<ScalarDistribution> laws{
      ScalarDistribution::truncated_normal(0, 1, 8, 9),
      ScalarDistribution::truncated_normal(0, 1, -29, -28),
      ScalarDistribution::truncated_normal(5, 1e-3, 4.9999, 5.0001),
      ScalarDistribution::truncated_lognormal(1, 2, 1e-8, 1e-6),
      ScalarDistribution::truncated_lognormal(1e6, 0.1, 1e6, 1e6 + 1),
      ScalarDistribution::log_triangular(1e-9, 1e-9, 1e-1),
      ScalarDistribution::log_triangular(5e6, 6e6, 7e6),
      ScalarDistribution::triangular(-1, 0, 1),
      ScalarDistribution::uniform(3, 3)};
  for (const ScalarDistribution& law : laws) {
    SCOPED_TRACE(law.text());
    ASSERT_FALSE(law.validate().has_value()) << law.validate()->rule;
    const RandomStream stream(11, law.text());
    double smallest = law.max, largest = law.min;
    for (int i = 0; i < 100000; ++i) {
      const double x = law.sample(stream.get());
      ASSERT_TRUE(x >= law.min && x <= law.max) << "draw " << i << ": " << x;
      smallest = std::min(smallest, x);
      largest = std::max(largest, x);
    }
    EXPECT_GE(largest - smallest, 0.1 * (law.max - law.min)) << "the draws do not spread";
  }
}

TEST(ScalarDistribution, SameSeedAndNameSameDraws) {
  const ScalarDistribution law = ScalarDistribution::log_triangular(5e6, 6e6, 7e6);
  const auto draws = [&](std::uint64_t seed, const std::string& name) {
    const RandomStream stream(seed, name);
    std::vector<double> x(50);
    for (double& v : x) v = law.sample(stream.get());
    return x;
  };
  EXPECT_EQ(draws(7, "joints.tensile_strength"), draws(7, "joints.tensile_strength"));  // bit for bit
  EXPECT_NE(draws(7, "joints.tensile_strength"), draws(8, "joints.tensile_strength"));
  EXPECT_NE(draws(7, "joints.tensile_strength"), draws(7, "joints.friction_angle"));
  // The streams are seeded as the network generator's sets are (pinned there).
  EXPECT_EQ(stream_seed(1, "J1"), 2943102844ul);
  // A constant draws nothing from the stream.
  const RandomStream a(3, "s"), b(3, "s");
  EXPECT_EQ(ScalarDistribution::constant(4.5).sample(a.get()), 4.5);
  EXPECT_EQ(gsl_rng_get(a.get()), gsl_rng_get(b.get()));
}

TEST(ScalarDistribution, RulesNameTheParameterAndBothValues) {
  const auto error = [](const ScalarDistribution& law) {
    const auto e = law.validate();
    return e ? e->parameter + ": " + e->rule : std::string("no error");
  };
  EXPECT_EQ(error(ScalarDistribution::uniform(5e6, 1e6)), "max: min 5e6 > max 1e6: min must be <= max (swapped?)");
  EXPECT_EQ(error(ScalarDistribution::triangular(7e6, 6e6, 5e6)),
            "max: min 7e6 > max 5e6: min must be <= max (swapped?)");
  EXPECT_EQ(error(ScalarDistribution::triangular(1, 3, 2)), "mode: mode 3 lies outside [min, max] = [1, 2]");
  EXPECT_EQ(error(ScalarDistribution::log_triangular(1, 0.5, 2)), "mode: mode 0.5 lies outside [min, max] = [1, 2]");
  EXPECT_EQ(error(ScalarDistribution::log_triangular(0, 6e6, 7e6)),
            "min: must be > 0: log_triangular is a law of the logarithm of the value (got 0)");
  EXPECT_EQ(error(ScalarDistribution::truncated_lognormal(1e-3, 0.3, -1e-4, 2e-3)),
            "min: must be > 0: truncated_lognormal is a law of the logarithm of the value (got -1e-4)");
  EXPECT_EQ(error(ScalarDistribution::truncated_normal(4, 0, 3, 5)), "std: must be > 0 (got 0)");
  EXPECT_EQ(error(ScalarDistribution::truncated_lognormal(0, 0.3, 1, 2)), "median: must be > 0 (got 0)");
  EXPECT_EQ(error(ScalarDistribution::truncated_normal(0, 1, 31, 32)),
            "min: [min, max] = [31, 32] lies more than 30 standard deviations from the mean, where the normal law "
            "holds no probability a double can resolve");
  EXPECT_EQ(error(ScalarDistribution::uniform(1, std::nan(""))), "max: must be a finite number (got nan)");
  EXPECT_EQ(error(ScalarDistribution::triangular(1, 1, 1)), "no error");  // the seed's density: min = mode = max
  EXPECT_EQ(error(ScalarDistribution::truncated_normal(0, 1, 2, 3)), "no error");
}

}  // namespace
}  // namespace hfdda::stochastic

namespace hfdda::io {
namespace {

using namespace case_test;

TEST(DistributionKeys, ReadIntoTheLawBesideTheNumber) {
  const CaseConfig c = load_case_text(R"(
random_seed: 3
materials:
  - {youngs_modulus: {distribution: triangular, min: 8.0e9, mode: 10.0e9, max: 12.0e9}, poissons_ratio: 0.22}
joints:
  tensile_strength: {distribution: log_triangular, min: 5.7e6, mode: 9.02e6, max: 12.4e6}
  friction_angle: 30
far_field: {sxx: {distribution: uniform, min: -12.0e6, max: -8.0e6}, sides: [left, right]}
)",
                                      "case.yaml");
  EXPECT_EQ(c.random_seed, 3);
  ASSERT_TRUE(c.materials[0].youngs_modulus_law.has_value());
  EXPECT_EQ(c.materials[0].youngs_modulus_law->kind, stochastic::DistributionKind::triangular);
  EXPECT_EQ(c.materials[0].youngs_modulus_law->max, 12e9);
  EXPECT_EQ(c.materials[0].youngs_modulus_Pa, 10e9);  // the mode stands for the law
  EXPECT_FALSE(c.materials[0].poissons_ratio_law.has_value());
  ASSERT_TRUE(c.joints.tensile_strength_law.has_value());
  EXPECT_EQ(c.joints.tensile_strength_law->text(), "log_triangular(min 5700000, mode 9020000, max 12400000)");
  EXPECT_EQ(c.far_field.sxx_Pa, -10e6);
  EXPECT_TRUE(has_distributions(c));
  // Without distributions the keys read as before, with the default seed.
  const CaseConfig plain = load_case_text("joints: {tensile_strength: 6.0e6}\n", "case.yaml");
  EXPECT_FALSE(has_distributions(plain));
  EXPECT_EQ(plain.random_seed, 1);
  EXPECT_EQ(plain.joints.tensile_strength_Pa, 6e6);
}

TEST(DistributionKeys, BadLawsNameFileLineKeyAndRule) {
  // Table 5.6 prints the tensile strength's min and max swapped (erratum 9): refused,
  // naming both values.
  expect_text_error("joints:\n  tensile_strength:\n    distribution: triangular\n    min: 12.4e6\n    mode: 9.02e6\n"
                    "    max: 5.7e6\n",
                    6, "joints.tensile_strength.max", "min 12400000 > max 5700000: min must be <= max");
  expect_text_error("joints: {friction_angle: {distribution: triangular, min: 25, mode: 40, max: 35}}\n", 1,
                    "joints.friction_angle.mode", "mode 40 lies outside [min, max] = [25, 35]");
  expect_text_error("joints: {hydraulic_width: {distribution: log_triangular, min: 0, mode: 1.0e-4, max: 2.0e-4}}\n",
                    1, "joints.hydraulic_width.min", "must be > 0: log_triangular is a law of the logarithm");
  expect_text_error("fluid:\n  viscosity: {distribution: truncated_lognormal, median: 2.0e-2, sigma: 0.5,\n"
                    "              min: -1, max: 0.1}\ninjections: [{at: [0, 0], mass_rate: 1}]\n",
                    3, "fluid.viscosity.min", "must be > 0: truncated_lognormal");
  expect_text_error("materials: [{poissons_ratio: {distribution: uniform, min: 0.2, max: 0.6}}]\n", 1,
                    "materials[0].poissons_ratio.max",
                    "must be in [0, 0.5), the allowed range of the key itself (got 0.6)");
  expect_text_error("materials: [{youngs_modulus: {distribution: uniform, min: 1, mode: 2, max: 3}}]\n", 1,
                    "materials[0].youngs_modulus.mode", "is not used by distribution uniform takes min, max");
  expect_text_error("far_field: {syy: {distribution: truncated_normal, mean: -1.0e7, min: -1.2e7, max: -8.0e6}}\n", 1,
                    "far_field.syy.std", "is required: distribution truncated_normal takes mean, std, min, max");
  expect_text_error("far_field: {syy: {distribution: normal, mean: -1.0e7, std: 1.0e6}}\n", 1,
                    "far_field.syy.distribution",
                    "must be one of: uniform, triangular, log_triangular, truncated_normal, truncated_lognormal");
  expect_text_error("far_field: {syy: {min: 1, max: 2}}\n", 1, "far_field.syy.distribution", "is required");
  expect_text_error("far_field: {syy: {distribution: truncated_normal, mean: 0, std: 0, min: -1, max: 1}}\n", 1,
                    "far_field.syy.std", "must be > 0 (got 0)");
  expect_text_error("far_field: {syy: [1, 2]}\n", 1, "far_field.syy",
                    "expected a number or a distribution map {distribution: ..., ...} (got a list)");
  expect_text_error("random_seed: 4\njoints: {tensile_strength: 6.0e6}\n", 1, "random_seed",
                    "is only used by keys given as distributions (there is none)");
  expect_text_error("random_seed: -1\n", 1, "random_seed", "must be in [0, 2147483647]");
  // The key's own range holds for every value of the law, and the side checks see the law.
  expect_text_error("far_field: {sxx: {distribution: uniform, min: -2.0e10, max: 0}}\n", 1, "far_field.sxx.min",
                    "must be in [-1e10, 1e10]");
  // (its mode, 0, stands for it in the config; the law can give -2e6)
  expect_text_error("far_field: {sxx: {distribution: triangular, min: -2.0e6, mode: 0, max: 0}, sides: [top]}\n", 1,
                    "far_field.sxx", "acts only on the left and right sides");
}

TEST(DistributionKeys, ANumberLaterInTheChainReplacesALaw) {
  const std::string dir = std::string(HFDDA_TEST_OUTPUT_DIR) + "/distribution_extends";
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/base.yaml") << "joints: {friction_angle: {distribution: triangular, min: 25, mode: 30, "
                                       "max: 35}}\n";
  std::ofstream(dir + "/number.yaml") << "extends: base.yaml\njoints: {friction_angle: 33}\n";
  std::ofstream(dir + "/law.yaml") << "extends: number.yaml\njoints: {friction_angle: {distribution: uniform, "
                                      "min: 20, max: 40}}\n";
  EXPECT_TRUE(load_case_file(dir + "/base.yaml").joints.friction_angle_law.has_value());
  const CaseConfig number = load_case_file(dir + "/number.yaml");
  EXPECT_FALSE(number.joints.friction_angle_law.has_value());
  EXPECT_EQ(number.joints.friction_angle_deg, 33.0);
  const CaseConfig law = load_case_file(dir + "/law.yaml");
  ASSERT_TRUE(law.joints.friction_angle_law.has_value());
  EXPECT_EQ(law.joints.friction_angle_law->kind, stochastic::DistributionKind::uniform);
  EXPECT_EQ(law.joints.friction_angle_deg, 30.0);
}

TEST(DistributionKeys, TheReferenceDocumentsTheLawsAndTheirScope) {
  const std::string reference = case_file_reference_markdown();
  for (const char* text : {"## Distributions (`{distribution: ...}` maps)", "`random_seed`", "`log_triangular`",
                           "A distribution is drawn once per run.", "A distribution is drawn block by block",
                           "A distribution is drawn joint by joint", "number or distribution"})
    EXPECT_NE(reference.find(text), std::string::npos) << text;
}

}  // namespace
}  // namespace hfdda::io

namespace hfdda::simulation {
namespace {

using io::case_test::kCases;

const ParameterDraw* find_draw(const std::vector<ParameterDraw>& draws, const std::string& key) {
  for (const ParameterDraw& d : draws)
    if (d.key == key) return &d;
  return nullptr;
}

TEST(DistributionCase, DrawsPerRunPerBlockAndPerJointWithinTheirBounds) {
  const io::CaseConfig c = io::load_case_file(kCases + "distributions_kgd.yaml");
  const Model model = build_model(c);
  const dda::BlockSystem& system = *model.system;
  const mesh::Mesh& m = system.mesh();
  const std::vector<ParameterDraw>& draws = model.parameter_draws;

  // Once per run: the case as run holds the draws as numbers.
  const ParameterDraw* syy = find_draw(draws, "far_field.syy");
  const ParameterDraw* viscosity = find_draw(draws, "fluid.viscosity");
  const ParameterDraw* rate = find_draw(draws, "injections[0].mass_rate");
  ASSERT_TRUE(syy && viscosity && rate);
  for (const ParameterDraw* d : {syy, viscosity, rate}) {
    EXPECT_EQ(d->per, "run");
    EXPECT_EQ(d->count, 1);
  }
  EXPECT_EQ(model.config.far_field.syy_Pa, syy->min);
  EXPECT_FALSE(model.config.far_field.syy_law.has_value());
  EXPECT_TRUE(syy->min >= -2e5 && syy->min <= 0 && syy->min != -1e5);
  EXPECT_EQ(model.config.fluid->viscosity_Pa_s, viscosity->min);
  EXPECT_TRUE(viscosity->min >= 5e-4 && viscosity->min <= 2e-3);
  EXPECT_EQ(model.config.injections[0].mass_rate_kg_s, rate->min);
  EXPECT_TRUE(rate->min >= 3 && rate->min <= 5);
  EXPECT_EQ(find_draw(draws, "far_field.sxx"), nullptr);  // a number: nothing drawn

  // Block by block: every block its own modulus and ratio, within the law's bounds.
  const ParameterDraw* modulus = find_draw(draws, "materials[0].youngs_modulus");
  ASSERT_NE(modulus, nullptr);
  EXPECT_EQ(modulus->per, "block");
  EXPECT_EQ(modulus->count, system.n_blocks());
  std::set<double> moduli, ratios;
  for (int b = 0; b < system.n_blocks(); ++b) {
    const dda::Material& mat = system.materials()[system.block_material()[b]];
    EXPECT_TRUE(mat.youngs_modulus_Pa >= 20e9 && mat.youngs_modulus_Pa <= 30e9) << "block " << b;
    EXPECT_TRUE(mat.poissons_ratio >= 0.2 && mat.poissons_ratio <= 0.3) << "block " << b;
    EXPECT_EQ(mat.density_kg_m3, 2650.0);
    EXPECT_EQ(model.zone_of_material[system.block_material()[b]], 0);
    moduli.insert(mat.youngs_modulus_Pa);
    ratios.insert(mat.poissons_ratio);
  }
  EXPECT_EQ(static_cast<int>(moduli.size()), system.n_blocks());
  EXPECT_EQ(static_cast<int>(ratios.size()), system.n_blocks());
  EXPECT_NEAR(modulus->mean, 25e9, 0.05 * 25e9);  // symmetric triangle: mean = mode
  // The springs scale with the largest modulus the law can give, the same in every run.
  EXPECT_EQ(system.settings().normal_stiffness_N_m, 100 * 30e9);
  // The outputs write the zone, not the block's own material.
  for (int material : block_frame(system, model.zone_of_material).material) EXPECT_EQ(material, 0);

  // Joint by joint: friction on every joint (no fracture overrides it), T0 on path_left.
  const ParameterDraw* friction = find_draw(draws, "joints.friction_angle");
  const ParameterDraw* strength = find_draw(draws, "fractures[0].tensile_strength");
  ASSERT_TRUE(friction && strength);
  EXPECT_EQ(friction->per, "joint");
  EXPECT_EQ(friction->count, static_cast<int>(m.joints.size()));
  std::set<double> angles, strengths;
  int path_joints = 0;
  for (std::size_t j = 0; j < m.joints.size(); ++j) {
    const mesh::JointProperties& p = m.joints[j].properties;
    const double phi = p.friction_angle_rad * 180 / std::numbers::pi;
    EXPECT_TRUE(phi >= 25 - 1e-9 && phi <= 35 + 1e-9) << "joint " << j;
    angles.insert(phi);
    if (model.fracture_of_joint[j] == 0) {
      ++path_joints;
      EXPECT_TRUE(p.tensile_strength_Pa >= 1e3 && p.tensile_strength_Pa <= 1e5) << "joint " << j;
      strengths.insert(p.tensile_strength_Pa);
    } else {
      EXPECT_EQ(p.tensile_strength_Pa, 0.0) << "joint " << j;
    }
  }
  EXPECT_EQ(static_cast<int>(angles.size()), friction->count);
  EXPECT_EQ(path_joints, 5);
  EXPECT_EQ(strength->count, path_joints);
  EXPECT_EQ(static_cast<int>(strengths.size()), path_joints);

  // The same seed draws the same values, bit for bit; another seed others.
  const Model again = build_model(c);
  io::CaseConfig other_seed = c;
  other_seed.random_seed = 8;
  const Model other = build_model(other_seed);
  for (std::size_t j = 0; j < m.joints.size(); ++j) {
    const mesh::JointProperties& redrawn = again.system->mesh().joints[j].properties;
    EXPECT_EQ(redrawn.friction_angle_rad, m.joints[j].properties.friction_angle_rad);
    EXPECT_EQ(redrawn.tensile_strength_Pa, m.joints[j].properties.tensile_strength_Pa);
  }
  EXPECT_EQ(again.config.far_field.syy_Pa, model.config.far_field.syy_Pa);
  EXPECT_EQ(again.system->materials().size(), system.materials().size());
  for (std::size_t k = 0; k < system.materials().size(); ++k)
    EXPECT_EQ(again.system->materials()[k].youngs_modulus_Pa, system.materials()[k].youngs_modulus_Pa);
  EXPECT_NE(other.config.far_field.syy_Pa, model.config.far_field.syy_Pa);
  EXPECT_NE(other.system->materials()[1].youngs_modulus_Pa, system.materials()[1].youngs_modulus_Pa);
}

TEST(DistributionCase, RunsAndRecordsItsDrawsInTheSummary) {
  const io::CaseConfig c = io::load_case_file(kCases + "distributions_kgd.yaml");
  Model model = build_model(c);
  RunOptions options;
  options.output_dir = std::string(HFDDA_TEST_OUTPUT_DIR) + "/distributions_run";
  options.quiet = true;
  std::filesystem::remove_all(options.output_dir);
  const RunResult result = run(model, options);
  ASSERT_TRUE(result.completed) << result.message;
  EXPECT_EQ(result.steps, 2);
  nlohmann::json summary;
  std::ifstream(options.output_dir + "/summary.json") >> summary;
  EXPECT_EQ(summary["random_seed"], 7);
  const nlohmann::json& drawn = summary["sampled_parameters"];
  ASSERT_EQ(drawn.size(), model.parameter_draws.size());
  std::set<std::string> keys;
  for (const nlohmann::json& d : drawn) {
    const std::string key = d["key"];
    keys.insert(key);
    if (d["per"] == "run") {
      EXPECT_TRUE(d.contains("value")) << key;
    } else {
      EXPECT_LE(d["min"].get<double>(), d["mean"].get<double>()) << key;
      EXPECT_LE(d["mean"].get<double>(), d["max"].get<double>()) << key;
      EXPECT_GT(d["count"].get<int>(), 1) << key;
    }
  }
  EXPECT_EQ(keys, (std::set<std::string>{"far_field.syy", "fluid.viscosity", "injections[0].mass_rate",
                                         "materials[0].youngs_modulus", "materials[0].poissons_ratio",
                                         "joints.friction_angle", "fractures[0].tensile_strength"}));
  const auto viscosity =
      std::find_if(drawn.begin(), drawn.end(), [](const auto& d) { return d["key"] == "fluid.viscosity"; });
  EXPECT_EQ((*viscosity)["distribution"], "truncated_lognormal(median 0.001, sigma 0.3, min 5e-4, max 0.002)");
  EXPECT_EQ((*viscosity)["value"].get<double>(), model.config.fluid->viscosity_Pa_s);
}

constexpr const char* kSetLawCase = R"(title: network with drawn properties
domain: {outer: {xmin: -40, xmax: 40, ymin: -40, ymax: 40}}
mesh: {type: delaunay, max_area_inner: 4}
joints:
  tensile_strength: {distribution: log_triangular, min: 5.0e6, mode: 6.0e6, max: 7.0e6}
  friction_angle: 30
fractures:
  - {name: cut, from: [-30, 0], to: [30, 0], fracture_toughness: 1.0e6}
network_seed: 9
random_seed: 5
fracture_sets:
  - name: J1
    azimuth: 45
    seed_fraction: 0.3
    length: {distribution: triangular, min: 10, mode: 15, max: 30}
    tensile_strength: 0
    friction_angle: {distribution: triangular, min: 25, mode: 30, max: 35}
    hydraulic_width: {distribution: log_triangular, min: 80.0e-6, mode: 100.0e-6, max: 200.0e-6}
  - {name: J2, azimuth: 135, seed_fraction: 0.3, length: {distribution: lognormal, median: 12, sigma: 0.3}}
)";

TEST(DistributionCase, SetPropertiesAreDrawnJointByJoint) {
  // Table 5.5's natural fractures: friction triangular 25-35 deg, w0 triangular on log10,
  // 80-200 um, one draw per joint of the set's fractures.
  const io::CaseConfig c = io::load_case_text(kSetLawCase, "case.yaml");
  const FracturedMesh fractured = build_fractured_mesh(c);
  const mesh::Mesh& m = fractured.mesh;
  std::set<double> widths, angles;
  int set_joints = 0, rock_joints = 0;
  for (std::size_t j = 0; j < m.joints.size(); ++j) {
    const int f = fractured.fracture_of_joint[j];
    const mesh::JointProperties& p = m.joints[j].properties;
    const int set = f < 0 ? -1 : fractured.fractures[f].set;
    SCOPED_TRACE("joint " + std::to_string(j));
    if (set == 0) {
      ++set_joints;
      EXPECT_EQ(p.tensile_strength_Pa, 0.0);
      const double phi = p.friction_angle_rad * 180 / std::numbers::pi;
      EXPECT_TRUE(phi >= 25 - 1e-9 && phi <= 35 + 1e-9) << phi;
      EXPECT_TRUE(p.hydraulic_width_m >= 80e-6 && p.hydraulic_width_m <= 200e-6) << p.hydraulic_width_m;
      widths.insert(p.hydraulic_width_m);
      angles.insert(phi);
    } else if (f == 0) {  // K_IC sets T0 on the cut: no T0 drawn
      EXPECT_TRUE(p.fracture_toughness_Pa_sqrt_m.has_value());
      EXPECT_EQ(p.tensile_strength_Pa, 6e6);  // the law's mode, never used
    } else {  // `joints`' law, J2's joints included (the set sets no T0)
      ++rock_joints;
      EXPECT_TRUE(p.tensile_strength_Pa >= 5e6 && p.tensile_strength_Pa <= 7e6) << p.tensile_strength_Pa;
      EXPECT_EQ(p.hydraulic_width_m, 0.0);
      EXPECT_NEAR(p.friction_angle_rad, 30 * std::numbers::pi / 180, 1e-15);
    }
  }
  EXPECT_GT(set_joints, 20);
  EXPECT_EQ(static_cast<int>(widths.size()), set_joints);
  EXPECT_EQ(static_cast<int>(angles.size()), set_joints);
  EXPECT_GT(rock_joints, 1000);
  // The network does not depend on random_seed, only on network_seed.
  io::CaseConfig other = c;
  other.random_seed = 6;
  const FracturedMesh redrawn = build_fractured_mesh(other);
  EXPECT_EQ(redrawn.fracture_of_joint, fractured.fracture_of_joint);
  int changed = 0;
  for (std::size_t j = 0; j < m.joints.size(); ++j)
    changed += redrawn.mesh.joints[j].properties.hydraulic_width_m != m.joints[j].properties.hydraulic_width_m;
  EXPECT_EQ(changed, set_joints);
}

TEST(DistributionCase, ACaseWithoutDistributionsDrawsNothing) {
  const Model model = build_model(io::load_case_file(kCases + "restart_kgd.yaml"));
  EXPECT_TRUE(model.parameter_draws.empty());
  EXPECT_EQ(model.zone_of_material, std::vector<int>{0});
  EXPECT_EQ(model.system->materials().size(), 1u);
}

}  // namespace
}  // namespace hfdda::simulation
