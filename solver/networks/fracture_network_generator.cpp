// Fracture networks grown on the joints of a mesh (W. E. Morgan, PhD dissertation,
// Georgia Institute of Technology, 2014, section 5.3); see the header for the method
// and conventions.

#include "networks/fracture_network_generator.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <deque>
#include <limits>
#include <numbers>

#include "core/errors.hpp"
#include "stochastic/scalar_distribution.hpp"

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

/// The law of a set's target lengths as a scalar distribution (one sampler for the
/// lengths and the case-file parameters).
stochastic::ScalarDistribution length_distribution(const LengthLaw& law) {
  using stochastic::ScalarDistribution;
  switch (law.distribution) {
    case LengthDistribution::uniform: return ScalarDistribution::uniform(law.min_m, law.max_m);
    case LengthDistribution::triangular: return ScalarDistribution::triangular(law.min_m, law.mode_m, law.max_m);
    case LengthDistribution::lognormal: return ScalarDistribution::lognormal(law.median_m, law.sigma);
    case LengthDistribution::power_law: return ScalarDistribution::power_law(law.exponent, law.min_m, law.max_m);
  }
  return ScalarDistribution::uniform(law.min_m, law.max_m);
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

double length_cdf(const LengthLaw& law, double x) { return length_distribution(law).cdf(x); }

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
  return stochastic::stream_seed(seed, set_name);
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
    const stochastic::RandomStream rng(seed, set.name);
    // All draws first, in joint-id order, so they do not depend on how fractures grow.
    const Vec2 a = azimuth_vector(set.azimuth_deg);
    for (int j = 0; j < static_cast<int>(m.joints.size()); ++j) {
      if (!reserved.empty() && reserved[j]) continue;
      const Vec2 d = m.points[m.joints[j].point_q] - m.points[m.joints[j].point_p];
      if (line_angle_deg(d, a) > set.azimuth_tolerance_deg) continue;
      ++stats.candidates;
      if (gsl_rng_uniform(rng.get()) < set.seed_fraction) stats.seed_draws.push_back({j, 0.0, -1});
    }
    const stochastic::ScalarDistribution length = length_distribution(set.length);
    for (SeedDraw& s : stats.seed_draws) s.target_length_m = length.sample(rng.get());
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
