// The fracture-network generator (W. E. Morgan, PhD dissertation, Georgia Institute of
// Technology, 2014, section 5.3): every joint within its tolerance of the set's azimuth,
// the seed fraction within a binomial bound, the target lengths of each distribution
// (Kolmogorov-Smirnov against CDFs written here, independently of the generator), the
// achieved lengths within a joint of their targets, reproducibility from the seed, the
// validation of the settings and case-file keys, and the set's values on the model's joints.

#include <gsl/gsl_rng.h>
#include <gtest/gtest.h>

#include "statistics_support.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "io/case_config.hpp"
#include "mesh/mesh.hpp"
#include "networks/fracture_network_generator.hpp"
#include "simulation/model.hpp"
#include "test_case_support.hpp"

namespace hfdda::networks {
namespace {

/// A Delaunay mesh of the square [-half, half]^2 with triangles of at most max_area.
mesh::Mesh square_mesh(double half_m, double max_area_m2) {
  mesh::DelaunayMeshSpec spec;
  spec.outer = Rect{-half_m, half_m, -half_m, half_m};
  spec.max_area_inner_m2 = spec.max_area_outer_m2 = max_area_m2;
  mesh::Mesh m = mesh::build_delaunay_mesh(spec);
  mesh::build_topology(m, mesh::JointProperties{});
  return m;
}

double joint_length(const mesh::Mesh& m, int j) {
  return (m.points[m.joints[j].point_q] - m.points[m.joints[j].point_p]).norm();
}

double longest_joint(const mesh::Mesh& m) {
  double longest = 0.0;
  for (int j = 0; j < static_cast<int>(m.joints.size()); ++j) longest = std::max(longest, joint_length(m, j));
  return longest;
}

FractureSetSettings uniform_set(const std::string& name, double azimuth_deg, double fraction, double min_m,
                                double max_m) {
  FractureSetSettings s;
  s.name = name;
  s.azimuth_deg = azimuth_deg;
  s.seed_fraction = fraction;
  s.length.distribution = LengthDistribution::uniform;
  s.length.min_m = min_m;
  s.length.max_m = max_m;
  return s;
}

using test::ks_critical;
using test::ks_statistic;

// The CDFs of the four laws, written from their definitions (not the generator's).
double uniform_cdf(double x, double a, double b) { return std::clamp((x - a) / (b - a), 0.0, 1.0); }
double triangular_cdf(double x, double a, double c, double b) {
  if (x <= a) return 0.0;
  if (x >= b) return 1.0;
  return x <= c ? (x - a) * (x - a) / ((b - a) * (c - a)) : 1.0 - (b - x) * (b - x) / ((b - a) * (b - c));
}
double lognormal_cdf(double x, double median, double sigma) {
  return x <= 0.0 ? 0.0 : 0.5 * std::erfc(-(std::log(x) - std::log(median)) / (sigma * std::numbers::sqrt2));
}
double power_law_cdf(double x, double a, double lo, double hi) {
  if (x <= lo) return 0.0;
  if (x >= hi) return 1.0;
  // integral of t^-a from lo to x over the one from lo to hi
  return (std::pow(x, 1.0 - a) - std::pow(lo, 1.0 - a)) / (std::pow(hi, 1.0 - a) - std::pow(lo, 1.0 - a));
}

TEST(NetworkGenerator, EveryJointLiesWithinItsToleranceOfTheAzimuth) {
  // The seed's network (5.3, Figure 5.6): 250 m x 250 m, triangles <= 25 m^2, sets at
  // 45 and 135 degrees, +- 5 degrees, 12 %, 20 to 40 m; and a set at 0 degrees growing
  // within 30 degrees.
  const mesh::Mesh m = square_mesh(125, 25);
  std::vector<FractureSetSettings> sets{uniform_set("J1", 45, 0.12, 20, 40), uniform_set("J2", 135, 0.12, 20, 40),
                                        uniform_set("N", 0, 0.12, 20, 40)};
  sets[2].growth_tolerance_deg = 30;
  const FractureNetwork network = generate_fracture_network(m, sets, 1);
  ASSERT_EQ(network.sets.size(), 3u);
  for (std::size_t k = 0; k < sets.size(); ++k) {
    SCOPED_TRACE(sets[k].name);
    // Candidates: every joint within the tolerance, counted here from the joint azimuths.
    int candidates = 0;
    for (int j = 0; j < static_cast<int>(m.joints.size()); ++j)
      candidates += azimuth_difference_deg(joint_azimuth_deg(m, j), sets[k].azimuth_deg) <= 5.0;
    EXPECT_EQ(network.sets[k].candidates, candidates);
    EXPECT_GT(candidates, 200);
    EXPECT_GT(network.sets[k].fractures, 20);
  }
  std::vector<int> owner(m.joints.size(), -1);
  int steps = 0, steps_beyond_45 = 0;
  for (std::size_t f = 0; f < network.fractures.size(); ++f) {
    const GeneratedFracture& fr = network.fractures[f];
    const FractureSetSettings& set = sets[fr.set];
    SCOPED_TRACE(fr.name);
    EXPECT_LE(azimuth_difference_deg(joint_azimuth_deg(m, fr.seed_joint), set.azimuth_deg),
              set.azimuth_tolerance_deg + 1e-9);
    double length = 0.0;
    const Vec2 a(std::sin(set.azimuth_deg * std::numbers::pi / 180), std::cos(set.azimuth_deg * std::numbers::pi / 180));
    for (std::size_t i = 0; i < fr.joints.size(); ++i) {
      const int j = fr.joints[i];
      EXPECT_LE(azimuth_difference_deg(joint_azimuth_deg(m, j), set.azimuth_deg), set.growth_tolerance_deg + 1e-9);
      steps += j != fr.seed_joint;
      steps_beyond_45 += azimuth_difference_deg(joint_azimuth_deg(m, j), set.azimuth_deg) > 45 - 1e-9;
      EXPECT_EQ(owner[j], -1) << "joint " << j << " in two fractures";
      owner[j] = static_cast<int>(f);
      EXPECT_EQ(network.fracture_of_joint[j], static_cast<int>(f));
      length += joint_length(m, j);
      if (i == 0) continue;
      // A chain: consecutive joints share a point, and the fracture advances along the azimuth.
      const mesh::Joint& prev = m.joints[fr.joints[i - 1]];
      const mesh::Joint& cur = m.joints[j];
      const int shared = (cur.point_p == prev.point_p || cur.point_p == prev.point_q) ? cur.point_p : cur.point_q;
      ASSERT_TRUE(shared == prev.point_p || shared == prev.point_q) << "joints " << fr.joints[i - 1] << ", " << j;
      const auto along = [&](const mesh::Joint& jt, int from) {
        const int to = jt.point_p == from ? jt.point_q : jt.point_p;
        return (m.points[to] - m.points[from]).dot(a);
      };
      if (i == 1) {
        const int start = prev.point_p == shared ? prev.point_q : prev.point_p;
        EXPECT_GT(along(prev, start) * along(cur, shared), 0.0) << "the fracture turns back";
      }
    }
    EXPECT_NEAR(fr.length_m, length, 1e-9 * length);
  }
  for (std::size_t j = 0; j < m.joints.size(); ++j) EXPECT_EQ(network.fracture_of_joint[j], owner[j]);
  EXPECT_GT(steps, 300);
  std::printf("growth steps %d, %d of them onto a joint more than 45 deg off the azimuth\n", steps, steps_beyond_45);
}

TEST(NetworkGenerator, SeedFractionIsWithinABinomialBound) {
  const mesh::Mesh m = square_mesh(100, 4);
  for (const double p : {0.06, 0.12, 0.5, 1.0})
    for (const std::uint64_t seed : {1u, 2u, 3u}) {
      FractureSetSettings set = uniform_set("S", 30, p, 5, 10);
      set.azimuth_tolerance_deg = 30;
      const FractureNetwork network = generate_fracture_network(m, {set}, seed);
      const SetStatistics& s = network.sets[0];
      const double n = s.candidates, mean = p * n, sd = std::sqrt(n * p * (1 - p));
      EXPECT_GT(n, 5000);
      EXPECT_LE(std::abs(s.seeds - mean), 4 * sd + 1e-9) << "p " << p << ", seed " << seed << ": " << s.seeds
                                                         << " seeds of " << n << " candidates";
      EXPECT_EQ(static_cast<int>(s.seed_draws.size()), s.seeds);
      EXPECT_EQ(s.seeds, s.fractures + s.absorbed_seeds);
    }
}

TEST(NetworkGenerator, TargetLengthsFollowTheirDistribution) {
  // Nearly every joint a seed: thousands of draws per law, tested against CDFs written
  // from the definitions; the generator's own length_cdf is checked against them too.
  const mesh::Mesh m = square_mesh(60, 2);
  struct Case {
    const char* name;
    LengthLaw law;
    std::function<double(double)> cdf;
  };
  LengthLaw uniform{LengthDistribution::uniform, 20, 40};
  LengthLaw triangular{LengthDistribution::triangular, 20, 40};
  triangular.mode_m = 25;
  LengthLaw lognormal{LengthDistribution::lognormal};
  lognormal.median_m = 30;
  lognormal.sigma = 0.4;
  LengthLaw power{LengthDistribution::power_law, 10, 100};
  power.exponent = 2.5;
  LengthLaw power_one{LengthDistribution::power_law, 10, 100};
  power_one.exponent = 1.0;
  const std::vector<Case> cases{
      {"uniform", uniform, [](double x) { return uniform_cdf(x, 20, 40); }},
      {"triangular", triangular, [](double x) { return triangular_cdf(x, 20, 25, 40); }},
      {"lognormal", lognormal, [](double x) { return lognormal_cdf(x, 30, 0.4); }},
      {"power_law a = 2.5", power, [](double x) { return power_law_cdf(x, 2.5, 10, 100); }},
      {"power_law a = 1", power_one, [](double x) {
         return x <= 10 ? 0.0 : x >= 100 ? 1.0 : std::log(x / 10) / std::log(10.0);
       }}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    FractureSetSettings set = uniform_set("L", 0, 1.0, 1, 1);
    set.azimuth_tolerance_deg = 89.99;
    set.length = c.law;
    for (const std::uint64_t seed : {7u, 8u}) {
      const FractureNetwork network = generate_fracture_network(m, {set}, seed);
      std::vector<double> targets;
      for (const SeedDraw& s : network.sets[0].seed_draws) targets.push_back(s.target_length_m);
      ASSERT_GT(targets.size(), 8000u);
      const double d = ks_statistic(targets, c.cdf);
      EXPECT_LT(d, ks_critical(targets.size())) << "seed " << seed << ", " << targets.size() << " draws";
    }
    for (double x = 0.5; x < 150; x += 0.5) EXPECT_NEAR(length_cdf(c.law, x), c.cdf(x), 1e-12) << "x = " << x;
  }
}

TEST(NetworkGenerator, AchievedLengthsAreWithinAJointOfTheTarget) {
  // Joints of about 1.5 m, fractures of 20 to 40 m: the lengths grown to are quantised by
  // the joints. Where growth was not blocked, the length is the target to within half a
  // joint (a joint is added only if it brings the length closer to the target).
  const mesh::Mesh m = square_mesh(100, 1);
  const double half_joint = 0.5 * longest_joint(m);
  std::vector<FractureSetSettings> sets{uniform_set("A", 45, 0.03, 20, 40), uniform_set("B", 120, 0.03, 20, 40)};
  const FractureNetwork network = generate_fracture_network(m, sets, 5);
  std::vector<double> achieved, targets;
  double bias = 0.0;
  int blocked = 0;
  for (const GeneratedFracture& f : network.fractures) {
    if (!f.reached_target) {
      ++blocked;
      EXPECT_LT(f.length_m, f.target_length_m) << f.name;
      continue;
    }
    EXPECT_LE(std::abs(f.length_m - f.target_length_m), half_joint + 1e-9) << f.name;
    achieved.push_back(f.length_m);
    targets.push_back(f.target_length_m);
    bias += f.length_m - f.target_length_m;
  }
  const std::size_t n = achieved.size();
  ASSERT_GT(n, 100u);
  EXPECT_LT(blocked, static_cast<int>(n) / 5) << "most fractures reach their length on a fine mesh";
  bias /= static_cast<double>(n);
  EXPECT_LT(std::abs(bias), 0.25 * half_joint) << "the lengths are rounded, not cut or stretched";
  // Achieved lengths against the target law: within the KS bound widened by the largest
  // change of the CDF over half a joint (each length is its target moved by at most that).
  const double widen = half_joint / 20.0;
  const double d = ks_statistic(achieved, [](double x) { return uniform_cdf(x, 20, 40); });
  EXPECT_LT(d, ks_critical(n) + widen);
  std::printf("achieved lengths: %zu fractures reached their target, %d blocked; mean bias %.3f m, "
              "KS %.4f (bound %.4f), half joint %.2f m\n",
              n, blocked, bias, d, ks_critical(n) + widen, half_joint);
}

TEST(NetworkGenerator, SameSeedSameNetworkOtherSeedOtherNetwork) {
  const mesh::Mesh m = square_mesh(125, 25);
  const std::vector<FractureSetSettings> sets{uniform_set("J1", 45, 0.12, 20, 40),
                                              uniform_set("J2", 135, 0.12, 20, 40)};
  const FractureNetwork a = generate_fracture_network(m, sets, 42);
  const FractureNetwork b = generate_fracture_network(m, sets, 42);
  const FractureNetwork c = generate_fracture_network(m, sets, 43);
  ASSERT_EQ(a.fractures.size(), b.fractures.size());
  for (std::size_t f = 0; f < a.fractures.size(); ++f) {
    EXPECT_EQ(a.fractures[f].joints, b.fractures[f].joints);
    EXPECT_EQ(a.fractures[f].target_length_m, b.fractures[f].target_length_m);  // bit for bit
    EXPECT_EQ(a.fractures[f].name, b.fractures[f].name);
  }
  EXPECT_EQ(a.fracture_of_joint, b.fracture_of_joint);
  EXPECT_NE(a.fracture_of_joint, c.fracture_of_joint);
  // A third set, written first, leaves the draws of the two as they were (one generator
  // per set, seeded from its name).
  std::vector<FractureSetSettings> three = sets;
  three.insert(three.begin(), uniform_set("N", 0, 0.3, 10, 50));
  const FractureNetwork d = generate_fracture_network(m, three, 42);
  for (std::size_t k = 0; k < 2; ++k) {
    ASSERT_EQ(d.sets[k + 1].seed_draws.size(), a.sets[k].seed_draws.size());
    for (std::size_t i = 0; i < a.sets[k].seed_draws.size(); ++i) {
      EXPECT_EQ(d.sets[k + 1].seed_draws[i].joint, a.sets[k].seed_draws[i].joint);
      EXPECT_EQ(d.sets[k + 1].seed_draws[i].target_length_m, a.sets[k].seed_draws[i].target_length_m);
    }
  }
}

TEST(NetworkGenerator, GeneratorSeedingIsFixed) {
  // Changing how a set's generator is seeded changes every network of every case: this
  // pins the seeding (FNV-1a of the name, splitmix64 with the network seed, 32 bits) and
  // the first numbers of GSL's mt19937 behind it. The values were computed separately,
  // with the hash and Matsumoto and Nishimura's reference MT19937 (init_genrand) in Python.
  EXPECT_EQ(set_generator_seed(0, "J1"), 3924459596ul);
  EXPECT_EQ(set_generator_seed(1, "J1"), 2943102844ul);
  EXPECT_EQ(set_generator_seed(1, "J2"), 163484934ul);
  gsl_rng* rng = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(rng, set_generator_seed(1, "J1"));
  EXPECT_EQ(gsl_rng_get(rng), 601659433ul);
  EXPECT_EQ(gsl_rng_get(rng), 1780549880ul);
  gsl_rng_free(rng);
}

TEST(NetworkGenerator, ReservedJointsAreLeftAlone) {
  const mesh::Mesh m = square_mesh(50, 4);
  std::vector<char> reserved(m.joints.size(), 0);
  for (std::size_t j = 0; j < m.joints.size(); j += 3) reserved[j] = 1;
  FractureSetSettings set = uniform_set("R", 90, 0.5, 10, 20);
  set.azimuth_tolerance_deg = 20;
  const FractureNetwork network = generate_fracture_network(m, {set}, 3, reserved);
  ASSERT_FALSE(network.fractures.empty());
  for (const GeneratedFracture& f : network.fractures)
    for (int j : f.joints) EXPECT_FALSE(reserved[j]) << f.name << " took reserved joint " << j;
}

TEST(NetworkGenerator, InvalidSettingsNameTheKeyAndRule) {
  const mesh::Mesh m = square_mesh(10, 4);
  const auto error = [&](const std::function<void(FractureSetSettings&)>& change) -> std::string {
    FractureSetSettings s = uniform_set("S", 10, 0.1, 1, 2);
    change(s);
    try {
      generate_fracture_network(m, {uniform_set("ok", 0, 0.1, 1, 2), s}, 1);
    } catch (const ModelError& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_EQ(error([](auto& s) { s.seed_fraction = 0; }), "fracture_sets[1].seed_fraction: must be in (0, 1] (got 0)");
  EXPECT_EQ(error([](auto& s) { s.seed_fraction = 1.5; }), "fracture_sets[1].seed_fraction: must be in (0, 1] (got 1.5)");
  EXPECT_EQ(error([](auto& s) { s.azimuth_tolerance_deg = 90; }),
            "fracture_sets[1].azimuth_tolerance: must be in (0, 90) degrees (got 90)");
  EXPECT_EQ(error([](auto& s) { s.azimuth_tolerance_deg = 0; }),
            "fracture_sets[1].azimuth_tolerance: must be in (0, 90) degrees (got 0)");
  EXPECT_EQ(error([](auto& s) { s.growth_tolerance_deg = 91; }),
            "fracture_sets[1].growth_tolerance: must be in (0, 90] degrees (got 91)");
  EXPECT_EQ(error([](auto& s) { s.azimuth_deg = 180; }),
            "fracture_sets[1].azimuth: must be in [0, 180) degrees clockwise from the +y axis (got 180)");
  EXPECT_EQ(error([](auto& s) { s.length.min_m = 0; }), "fracture_sets[1].length.min: must be > 0 m (got 0)");
  EXPECT_EQ(error([](auto& s) { s.length.max_m = 0.5; }),
            "fracture_sets[1].length.max: must be >= length.min (got min 1, max 0.5)");
  EXPECT_EQ(error([](auto& s) {
              s.length.distribution = LengthDistribution::triangular;
              s.length.mode_m = 3;
            }),
            "fracture_sets[1].length.mode: must be in [length.min, length.max] (got min 1, mode 3, max 2)");
  EXPECT_EQ(error([](auto& s) { s.length.distribution = LengthDistribution::lognormal; }),
            "fracture_sets[1].length.median: must be > 0 m (got 0)");
  EXPECT_EQ(error([](auto& s) { s.name.clear(); }),
            "fracture_sets[1].name: must not be empty (it names the set's fractures)");
  EXPECT_EQ(error([](auto&) {}), "no error");
}

}  // namespace
}  // namespace hfdda::networks

namespace hfdda::io {
namespace {

using namespace case_test;

constexpr const char* kSetCase = R"(title: network
domain: {outer: {xmin: -40, xmax: 40, ymin: -40, ymax: 40}}
mesh: {type: delaunay, max_area_inner: 4}
joints: {tensile_strength: 6.0e6, cohesion: 1.0e6, friction_angle: 30, hydraulic_width: 0}
fractures:
  - {name: cut, from: [-30, 0], to: [30, 0], tensile_strength: 1.0e5}
network_seed: 9
fracture_sets:
  - name: J1
    azimuth: 45
    seed_fraction: 0.3
    length: {distribution: triangular, min: 10, mode: 15, max: 30}
    tensile_strength: 0
    cohesion: 0
    friction_angle: 35
    hydraulic_width: 1.0e-4
  - {name: J2, azimuth: 135, seed_fraction: 0.3, length: {distribution: lognormal, median: 12, sigma: 0.3}}
)";

TEST(FractureSetsCase, SetValuesReachTheModelJoints) {
  const CaseConfig c = load_case_text(kSetCase, "case.yaml");
  ASSERT_EQ(c.fracture_sets.size(), 2u);
  EXPECT_EQ(c.network_seed, 9);
  EXPECT_EQ(c.fracture_sets[0].azimuth_tolerance_deg, 5.0);  // the seed's +- 5 degrees by default
  const simulation::Model model = simulation::build_model(c);
  const mesh::Mesh& m = model.system->mesh();
  ASSERT_GT(model.network.fractures.size(), 4u);
  ASSERT_EQ(model.fractures.size(), 1 + model.network.fractures.size());
  EXPECT_EQ(model.fractures[0].name, "cut");
  EXPECT_EQ(model.fractures[0].config_index, 0);
  int per_set[2] = {0, 0};
  for (std::size_t n = 0; n < model.network.fractures.size(); ++n) {
    const simulation::ModelFracture& f = model.fractures[1 + n];
    const networks::GeneratedFracture& g = model.network.fractures[n];
    EXPECT_EQ(f.name, c.fracture_sets[g.set].name + "." + std::to_string(++per_set[g.set]));
    EXPECT_EQ(f.set, g.set);
    EXPECT_EQ(f.config_index, -1);
    for (int j : g.joints) {
      SCOPED_TRACE(f.name + ", joint " + std::to_string(j));
      EXPECT_EQ(model.fracture_of_joint[j], static_cast<int>(1 + n));
      const mesh::JointProperties& p = m.joints[j].properties;
      EXPECT_TRUE(p.natural);
      if (g.set == 0) {
        EXPECT_EQ(p.tensile_strength_Pa, 0.0);
        EXPECT_EQ(p.cohesion_Pa, 0.0);
        EXPECT_NEAR(p.friction_angle_rad, 35 * std::numbers::pi / 180, 1e-15);
        EXPECT_EQ(p.hydraulic_width_m, 1e-4);
      } else {  // unset values: those of `joints`
        EXPECT_EQ(p.tensile_strength_Pa, 6e6);
        EXPECT_EQ(p.cohesion_Pa, 1e6);
        EXPECT_NEAR(p.friction_angle_rad, 30 * std::numbers::pi / 180, 1e-15);
        EXPECT_EQ(p.hydraulic_width_m, 0.0);
      }
    }
  }
  EXPECT_GT(per_set[0], 0);
  EXPECT_GT(per_set[1], 0);
  int cut = 0, plain = 0;
  for (std::size_t j = 0; j < m.joints.size(); ++j) {
    const int f = model.fracture_of_joint[j];
    const mesh::JointProperties& p = m.joints[j].properties;
    if (f == 0) {  // the written fracture keeps its joints and values
      ++cut;
      EXPECT_EQ(p.tensile_strength_Pa, 1e5);
      EXPECT_FALSE(p.natural);
    } else if (f < 0) {
      ++plain;
      EXPECT_FALSE(p.natural);
      EXPECT_EQ(p.tensile_strength_Pa, 6e6);
    }
  }
  EXPECT_GT(cut, 10);
  EXPECT_GT(plain, 1000);
  // The same case gives the same network.
  EXPECT_EQ(simulation::build_model(c).fracture_of_joint, model.fracture_of_joint);
}

TEST(FractureSetsCase, BadKeysNameFileLineKeyAndRule) {
  const std::string head = "mesh: {type: delaunay, max_area_inner: 4}\nfracture_sets:\n";
  expect_text_error(head + "  - {name: J1, azimuth: 45, seed_fraction: 0.1, length: {min: 1, max: 2}, spacing: 3}\n",
                    3, "fracture_sets[0].spacing", "unknown key; allowed keys: name, azimuth,");
  expect_text_error(head + "  - {name: J1, seed_fraction: 0.1, length: {min: 1, max: 2}}\n", 3,
                    "fracture_sets[0].azimuth", "is required");
  expect_text_error(head + "  - {name: J1, azimuth: 180, seed_fraction: 0.1, length: {min: 1, max: 2}}\n", 3,
                    "fracture_sets[0].azimuth", "must be in [0, 180) (got 180)");
  expect_text_error(head + "  - {name: J1, azimuth: 45, seed_fraction: 0, length: {min: 1, max: 2}}\n", 3,
                    "fracture_sets[0].seed_fraction", "must be in (0, 1] (got 0)");
  expect_text_error(head + "  - {name: J1, azimuth: 45, azimuth_tolerance: 90, seed_fraction: 0.1, "
                           "length: {min: 1, max: 2}}\n",
                    3, "fracture_sets[0].azimuth_tolerance", "must be in (0, 90) (got 90)");
  expect_text_error(head + "  - name: J1\n    azimuth: 45\n    seed_fraction: 0.1\n    length:\n      min: 3\n"
                           "      max: 2\n",
                    8, "fracture_sets[0].length.max", "must be >= min (got min 3, max 2)");
  expect_text_error(head + "  - {name: J1, azimuth: 45, seed_fraction: 0.1, length: {min: 1, median: 2, max: 3}}\n",
                    3, "fracture_sets[0].length.median", "is not used by distribution uniform takes min, max");
  expect_text_error(head + "  - {name: J1, azimuth: 45, seed_fraction: 0.1, length: {distribution: triangular, "
                           "min: 1, max: 3}}\n",
                    3, "fracture_sets[0].length.mode", "is required: distribution triangular takes min, mode, max");
  expect_text_error(head + "  - {name: J1, azimuth: 45, seed_fraction: 0.1, length: {distribution: triangular, "
                           "min: 1, mode: 4, max: 3}}\n",
                    3, "fracture_sets[0].length.mode", "must be in [min, max] (got min 1, mode 4, max 3)");
  expect_text_error(head + "  - {name: J1, azimuth: 45, seed_fraction: 0.1, length: {distribution: weibull}}\n", 3,
                    "fracture_sets[0].length.distribution",
                    "must be one of: uniform, triangular, lognormal, power_law (got 'weibull')");
  expect_text_error(head + "  - {name: J1, azimuth: 45, seed_fraction: 0.1, length: {distribution: power_law, "
                           "exponent: 2, min: 1}}\n",
                    3, "fracture_sets[0].length.max", "is required: distribution power_law takes exponent, min, max");
  expect_text_error(head + "  - {name: J-1, azimuth: 45, seed_fraction: 0.1, length: {min: 1, max: 2}}\n", 3,
                    "fracture_sets[0].name", "may contain only letters, digits and '_'");
  expect_text_error(head + "  - {name: J1, azimuth: 45, seed_fraction: 0.1, length: {min: 1, max: 2}}\n"
                           "  - {name: J1, azimuth: 90, seed_fraction: 0.1, length: {min: 1, max: 2}}\n",
                    4, "fracture_sets[1].name", "duplicate set name 'J1'");
  expect_text_error(head + "  - {name: J1, azimuth: 45, seed_fraction: 0.1, length: {min: 500, max: 600}}\n"
                           "domain: {outer: {xmin: 0, xmax: 100, ymin: 0, ymax: 100}}\n",
                    3, "fracture_sets[0].length.min", "must be <= the diagonal of domain.outer");
  expect_text_error("fractures: [{name: J1, from: [0, 0], to: [1, 0]}]\n" + head +
                        "  - {name: J1, azimuth: 45, seed_fraction: 0.1, length: {min: 1, max: 2}}\n",
                    4, "fracture_sets[0].name", "is also the name of fractures[0]");
  expect_text_error("fracture_sets:\n  - {name: J1, azimuth: 45, seed_fraction: 0.1, length: {min: 1, max: 2}}\n", 1,
                    "fracture_sets", "needs mesh.type: delaunay");
  expect_text_error("title: x\nnetwork_seed: 3\n", 2, "network_seed", "is only used with fracture_sets");
  expect_text_error(head + "  - {name: J1, azimuth: 45, seed_fraction: 0.1, length: {min: 1, max: 2}}\n"
                           "network_seed: -1\n",
                    4, "network_seed", "must be in [0, 2147483647] (got -1)");
}

}  // namespace
}  // namespace hfdda::io
