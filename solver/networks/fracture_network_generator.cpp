// Fracture networks grown on the joints of a mesh (W. E. Morgan, PhD dissertation,
// Georgia Institute of Technology, 2014, section 5.3); see the header for the method
// and conventions.

#include "networks/fracture_network_generator.hpp"

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <deque>
#include <limits>
#include <memory>
#include <numbers>

#include "core/errors.hpp"

namespace hfdda::networks {

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

std::string number_text(double v) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, result.ptr);
}

[[noreturn]] void fail(const std::string& key, const std::string& rule, double got) {
  throw ModelError(key + ": " + rule + " (got " + number_text(got) + ")");
}

/// Unit vector of an azimuth: clockwise from +y.
Vec2 azimuth_vector(double azimuth_deg) {
  return Vec2(std::sin(azimuth_deg * kDegree), std::cos(azimuth_deg * kDegree));
}

/// Angle between direction d and unit direction u [deg], in [0, 180].
double direction_angle_deg(const Vec2& d, const Vec2& u) {
  return std::atan2(std::abs(d.x() * u.y() - d.y() * u.x()), d.dot(u)) / kDegree;
}

/// Angle between the line along d and the line along u [deg], in [0, 90].
double line_angle_deg(const Vec2& d, const Vec2& u) {
  return std::atan2(std::abs(d.x() * u.y() - d.y() * u.x()), std::abs(d.dot(u))) / kDegree;
}

struct RngDeleter {
  void operator()(gsl_rng* r) const { gsl_rng_free(r); }
};
using Rng = std::unique_ptr<gsl_rng, RngDeleter>;

/// Inverse CDF of the triangular law (GSL has no triangular sampler).
double triangular_quantile(const LengthLaw& law, double u) {
  const double a = law.min_m, b = law.max_m, c = law.mode_m;
  if (b <= a) return a;
  if (u < (c - a) / (b - a)) return a + std::sqrt(u * (b - a) * (c - a));
  return b - std::sqrt((1.0 - u) * (b - a) * (b - c));
}

/// Inverse CDF of the density ~ L^-a truncated to [min, max] (GSL's Pareto law is not
/// truncated). Written in t = L / min with expm1 and log1p, so that neither a tiny min
/// nor an exponent near 1 loses the result to overflow or cancellation.
double power_law_quantile(const LengthLaw& law, double u) {
  const double lo = law.min_m, hi = law.max_m, k = 1.0 - law.exponent;
  if (hi <= lo) return lo;
  const double log_r = std::log(hi / lo);
  if (std::abs(k * log_r) < 1e-12) return std::clamp(lo * std::exp(u * log_r), lo, hi);
  return std::clamp(lo * std::exp(std::log1p(u * std::expm1(k * log_r)) / k), lo, hi);
}

double draw_length(gsl_rng* rng, const LengthLaw& law) {
  switch (law.distribution) {
    case LengthDistribution::uniform: return gsl_ran_flat(rng, law.min_m, law.max_m);
    case LengthDistribution::triangular: return triangular_quantile(law, gsl_rng_uniform(rng));
    case LengthDistribution::lognormal: return gsl_ran_lognormal(rng, std::log(law.median_m), law.sigma);
    case LengthDistribution::power_law: return power_law_quantile(law, gsl_rng_uniform(rng));
  }
  return 0.0;
}

/// Joints meeting at each mesh point, in ascending joint id.
std::vector<std::vector<int>> joints_at_points(const mesh::Mesh& m) {
  std::vector<std::vector<int>> at(m.points.size());
  for (int j = 0; j < static_cast<int>(m.joints.size()); ++j) {
    at[m.joints[j].point_p].push_back(j);
    at[m.joints[j].point_q].push_back(j);
  }
  return at;
}

double joint_length(const mesh::Mesh& m, int j) {
  return (m.points[m.joints[j].point_q] - m.points[m.joints[j].point_p]).norm();
}

int other_end(const mesh::Joint& joint, int point) { return joint.point_p == point ? joint.point_q : joint.point_p; }

/// Grows fracture `f` from its seed joint: at alternating ends, onto the joint at the
/// end point that runs closest to the azimuth in the outward direction, until the next
/// joint would leave it further from its target length than it is, or both ends are
/// blocked. Marks its joints in `owner`.
void grow(const mesh::Mesh& m, const std::vector<std::vector<int>>& joints_at, const FractureSetSettings& set,
          const std::vector<char>& reserved, int f, std::vector<int>& owner, GeneratedFracture& fracture) {
  struct End {
    int point;
    Vec2 outward;
    bool open = true;
  };
  const mesh::Joint& seed = m.joints[fracture.seed_joint];
  const Vec2 a = azimuth_vector(set.azimuth_deg);
  const bool q_ahead = (m.points[seed.point_q] - m.points[seed.point_p]).dot(a) >= 0.0;
  // ends[0] grows along +a (appended at the back of `chain`), ends[1] along -a (at the front).
  End ends[2] = {{q_ahead ? seed.point_q : seed.point_p, a}, {q_ahead ? seed.point_p : seed.point_q, -a}};
  std::deque<int> chain{fracture.seed_joint};
  owner[fracture.seed_joint] = f;
  double length = joint_length(m, fracture.seed_joint);
  bool reached = false;
  int turn = 0;
  while (!reached && (ends[0].open || ends[1].open)) {
    const int side = ends[turn].open ? turn : 1 - turn;
    turn = 1 - side;
    End& end = ends[side];
    int best = -1;
    double best_angle = std::numeric_limits<double>::infinity();
    for (int j : joints_at[end.point]) {
      if (owner[j] == f) continue;
      const Vec2 d = m.points[other_end(m.joints[j], end.point)] - m.points[end.point];
      if (d.dot(end.outward) <= 0.0) continue;  // it must advance along the azimuth
      const double angle = direction_angle_deg(d, end.outward);
      if (angle < best_angle) {  // ascending ids: a tie keeps the lower id
        best_angle = angle;
        best = j;
      }
    }
    // The closest joint decides: if it is too far off the azimuth, taken by another
    // fracture or one of the case's own, this end stops (the fractures meet there).
    if (best < 0 || best_angle > set.growth_tolerance_deg || owner[best] >= 0 ||
        (!reserved.empty() && reserved[best])) {
      end.open = false;
      continue;
    }
    const double l = joint_length(m, best);
    if (length + 0.5 * l > fracture.target_length_m) {  // closer to the target without it
      reached = true;
      break;
    }
    owner[best] = f;
    length += l;
    if (side == 0)
      chain.push_back(best);
    else
      chain.push_front(best);
    end.point = other_end(m.joints[best], end.point);
  }
  fracture.joints.assign(chain.begin(), chain.end());
  fracture.length_m = length;
  fracture.reached_target = reached || length >= fracture.target_length_m;
}

}  // namespace

double length_cdf(const LengthLaw& law, double x) {
  const double lo = law.min_m, hi = law.max_m;
  switch (law.distribution) {
    case LengthDistribution::uniform:
      if (hi <= lo) return x >= lo ? 1.0 : 0.0;
      return gsl_cdf_flat_P(x, lo, hi);
    case LengthDistribution::triangular: {
      const double c = law.mode_m;
      if (x <= lo) return hi <= lo && x == lo ? 1.0 : 0.0;
      if (x >= hi) return 1.0;
      if (x <= c) return (x - lo) * (x - lo) / ((hi - lo) * (c - lo));
      return 1.0 - (hi - x) * (hi - x) / ((hi - lo) * (hi - c));
    }
    case LengthDistribution::lognormal:
      return x <= 0.0 ? 0.0 : gsl_cdf_lognormal_P(x, std::log(law.median_m), law.sigma);
    case LengthDistribution::power_law: {
      if (x < lo) return 0.0;
      if (x >= hi) return 1.0;
      const double k = 1.0 - law.exponent, log_t = std::log(x / lo), log_r = std::log(hi / lo);
      if (std::abs(k * log_r) < 1e-12) return log_t / log_r;
      return std::expm1(k * log_t) / std::expm1(k * log_r);
    }
  }
  return 0.0;
}

void validate_settings(const FractureSetSettings& s, const std::string& prefix) {
  const auto key = [&](const std::string& name) { return prefix + "." + name; };
  const auto finite = [&](const std::string& name, double v) {
    if (!std::isfinite(v)) fail(key(name), "must be a finite number", v);
  };
  if (s.name.empty()) throw ModelError(key("name") + ": must not be empty (it names the set's fractures)");
  finite("azimuth", s.azimuth_deg);
  if (s.azimuth_deg < 0.0 || s.azimuth_deg >= 180.0)
    fail(key("azimuth"), "must be in [0, 180) degrees clockwise from the +y axis", s.azimuth_deg);
  finite("azimuth_tolerance", s.azimuth_tolerance_deg);
  if (!(s.azimuth_tolerance_deg > 0.0 && s.azimuth_tolerance_deg < 90.0))
    fail(key("azimuth_tolerance"), "must be in (0, 90) degrees", s.azimuth_tolerance_deg);
  finite("growth_tolerance", s.growth_tolerance_deg);
  if (!(s.growth_tolerance_deg > 0.0 && s.growth_tolerance_deg <= 90.0))
    fail(key("growth_tolerance"), "must be in (0, 90] degrees", s.growth_tolerance_deg);
  finite("seed_fraction", s.seed_fraction);
  if (!(s.seed_fraction > 0.0 && s.seed_fraction <= 1.0))
    fail(key("seed_fraction"), "must be in (0, 1]", s.seed_fraction);
  const LengthLaw& l = s.length;
  const std::string lk = key("length");
  const auto positive = [&](const std::string& name, double v) {
    finite("length." + name, v);
    if (!(v > 0.0)) fail(lk + "." + name, "must be > 0 m", v);
  };
  if (l.distribution == LengthDistribution::lognormal) {
    positive("median", l.median_m);
    positive("sigma", l.sigma);
    return;
  }
  positive("min", l.min_m);
  positive("max", l.max_m);
  if (l.max_m < l.min_m)
    throw ModelError(lk + ".max: must be >= length.min (got min " + number_text(l.min_m) + ", max " +
                     number_text(l.max_m) + ")");
  if (l.distribution == LengthDistribution::triangular && !(l.mode_m >= l.min_m && l.mode_m <= l.max_m))
    throw ModelError(lk + ".mode: must be in [length.min, length.max] (got min " + number_text(l.min_m) + ", mode " +
                     number_text(l.mode_m) + ", max " + number_text(l.max_m) + ")");
  if (l.distribution == LengthDistribution::power_law) finite("length.exponent", l.exponent);
}

double joint_azimuth_deg(const mesh::Mesh& m, int joint) {
  const Vec2 d = m.points[m.joints[joint].point_q] - m.points[m.joints[joint].point_p];
  double az = std::atan2(d.x(), d.y()) / kDegree;  // clockwise from +y, in (-180, 180]
  while (az < 0.0) az += 180.0;
  while (az >= 180.0) az -= 180.0;
  return az;
}

double azimuth_difference_deg(double a_deg, double b_deg) {
  double d = std::fmod(std::abs(a_deg - b_deg), 180.0);
  return std::min(d, 180.0 - d);
}

unsigned long set_generator_seed(std::uint64_t seed, const std::string& set_name) {
  // FNV-1a of the name, then splitmix64 of it with the seed: well-spread generator seeds
  // for neighbouring network seeds and similar names.
  std::uint64_t name_hash = 14695981039346656037ull;
  for (const char ch : set_name) {
    name_hash ^= static_cast<unsigned char>(ch);
    name_hash *= 1099511628211ull;
  }
  std::uint64_t z = seed * 0x9E3779B97F4A7C15ull + name_hash;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return static_cast<unsigned long>(z & 0xFFFFFFFFull);  // GSL's mt19937 uses 32 bits of its seed
}

FractureNetwork generate_fracture_network(const mesh::Mesh& m, const std::vector<FractureSetSettings>& sets,
                                          std::uint64_t seed, const std::vector<char>& reserved) {
  for (std::size_t k = 0; k < sets.size(); ++k) validate_settings(sets[k], "fracture_sets[" + std::to_string(k) + "]");
  if (!reserved.empty() && reserved.size() != m.joints.size())
    throw ModelError("generate_fracture_network: reserved has " + std::to_string(reserved.size()) +
                     " flags for " + std::to_string(m.joints.size()) + " joints");
  FractureNetwork network;
  network.fracture_of_joint.assign(m.joints.size(), -1);
  network.sets.resize(sets.size());
  const std::vector<std::vector<int>> joints_at = joints_at_points(m);
  for (std::size_t k = 0; k < sets.size(); ++k) {
    const FractureSetSettings& set = sets[k];
    SetStatistics& stats = network.sets[k];
    Rng rng(gsl_rng_alloc(gsl_rng_mt19937));
    if (!rng) throw ModelError("generate_fracture_network: cannot allocate a GSL generator");
    gsl_rng_set(rng.get(), set_generator_seed(seed, set.name));
    // All draws first, in joint-id order, so they do not depend on how fractures grow.
    const Vec2 a = azimuth_vector(set.azimuth_deg);
    for (int j = 0; j < static_cast<int>(m.joints.size()); ++j) {
      if (!reserved.empty() && reserved[j]) continue;
      const Vec2 d = m.points[m.joints[j].point_q] - m.points[m.joints[j].point_p];
      if (line_angle_deg(d, a) > set.azimuth_tolerance_deg) continue;
      ++stats.candidates;
      if (gsl_rng_uniform(rng.get()) < set.seed_fraction) stats.seed_draws.push_back({j, 0.0, -1});
    }
    for (SeedDraw& s : stats.seed_draws) s.target_length_m = draw_length(rng.get(), set.length);
    stats.seeds = static_cast<int>(stats.seed_draws.size());
    for (SeedDraw& s : stats.seed_draws) {
      if (network.fracture_of_joint[s.joint] >= 0) {
        ++stats.absorbed_seeds;
        continue;
      }
      GeneratedFracture fracture;
      fracture.set = static_cast<int>(k);
      fracture.name = set.name + "." + std::to_string(stats.fractures + 1);
      fracture.seed_joint = s.joint;
      fracture.target_length_m = s.target_length_m;
      s.fracture = static_cast<int>(network.fractures.size());
      grow(m, joints_at, set, reserved, s.fracture, network.fracture_of_joint, fracture);
      ++stats.fractures;
      stats.fractures_reaching_target += fracture.reached_target ? 1 : 0;
      stats.joints += static_cast<int>(fracture.joints.size());
      stats.total_length_m += fracture.length_m;
      network.fractures.push_back(std::move(fracture));
    }
  }
  return network;
}

}  // namespace hfdda::networks
