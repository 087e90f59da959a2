#include "fracture/toughness_criterion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Geometry>

namespace hfdda::fracture {

double plane_strain_modulus_Pa(double youngs_modulus_Pa, double poissons_ratio) {
  return youngs_modulus_Pa / (1.0 - poissons_ratio * poissons_ratio);
}

EnergyReleaseRates vcct_energy_release_rates(const CrackTip& t, CrackClosure closure) {
  if (!(t.length_m > 0.0) || !(t.behind_length_m > 0.0))
    throw std::invalid_argument("vcct_energy_release_rates: joint lengths must be > 0");
  // The opening at da behind the tip from the one at L_b: sqrt(r) near a tip.
  const double to_da = std::sqrt(t.length_m / t.behind_length_m);
  // A contact in compression, or faces pressed together, releases no Mode I energy.
  auto opening_work = [](double force_N, double opening_m) { return std::max(force_N, 0.0) * std::max(opening_m, 0.0); };
  const double closure_n = opening_work(t.tip_normal_N, t.far_opening_m * to_da) + opening_work(t.far_normal_N, t.near_opening_m);
  const double closure_s = t.tip_shear_N * t.far_slip_m * to_da + t.far_shear_N * t.near_slip_m;
  const double scale = kLumpedClosureFactor / (2.0 * t.length_m);
  const EnergyReleaseRates one_joint{scale * closure_n, scale * std::abs(closure_s)};
  if (closure == CrackClosure::one_joint || !(t.second_distance_m > 0.0)) return one_joint;
  // A closure of 2 da: the joint ahead's two forces at the tip, against the opening 2 da
  // behind it; then Richardson's extrapolation of G(da) and G(2 da) to da -> 0, with the
  // contact forces as they are (c = 1, see the header).
  const double to_2da = std::sqrt(2.0 * t.length_m / t.second_distance_m);
  const double closure2_n = (std::max(t.tip_normal_N, 0.0) + std::max(t.far_normal_N, 0.0)) *
                            std::max(t.second_opening_m * to_2da, 0.0);
  const double closure2_s = (t.tip_shear_N + t.far_shear_N) * t.second_slip_m * to_2da;
  const double scale1 = 1.0 / (2.0 * t.length_m), scale2 = 1.0 / (4.0 * t.length_m);
  return {std::max(2.0 * scale1 * closure_n - scale2 * closure2_n, 0.0),
          std::max(2.0 * scale1 * std::abs(closure_s) - scale2 * std::abs(closure2_s), 0.0)};
}

double stress_intensity_Pa_sqrt_m(double energy_release_rate_J_m2, double plane_strain_modulus_Pa) {
  return std::sqrt(std::max(energy_release_rate_J_m2, 0.0) * plane_strain_modulus_Pa);
}

double energy_release_rate_J_m2(double stress_intensity_Pa_sqrt_m, double plane_strain_modulus_Pa) {
  return stress_intensity_Pa_sqrt_m * stress_intensity_Pa_sqrt_m / plane_strain_modulus_Pa;
}

StressIntensities stress_intensities(const CrackTip& tip, CrackClosure closure) {
  const EnergyReleaseRates g = vcct_energy_release_rates(tip, closure);
  const double k2 = stress_intensity_Pa_sqrt_m(g.mode2_J_m2, tip.plane_strain_modulus_Pa);
  return {stress_intensity_Pa_sqrt_m(g.mode1_J_m2, tip.plane_strain_modulus_Pa), tip.far_slip_m < 0.0 ? -k2 : k2};
}

double mixed_mode_ratio(const EnergyReleaseRates& g, const Toughness& k, double modulus_Pa) {
  if (!(k.mode1_Pa_sqrt_m > 0.0) || !(k.mode2_Pa_sqrt_m > 0.0) || !(modulus_Pa > 0.0))
    throw std::invalid_argument("mixed_mode_ratio: toughnesses and modulus must be > 0");
  return g.mode1_J_m2 / energy_release_rate_J_m2(k.mode1_Pa_sqrt_m, modulus_Pa) +
         g.mode2_J_m2 / energy_release_rate_J_m2(k.mode2_Pa_sqrt_m, modulus_Pa);
}

double mixed_mode_ratio(const CrackTip& tip, const Toughness& toughness) {
  return mixed_mode_ratio(vcct_energy_release_rates(tip, toughness.closure), toughness, tip.plane_strain_modulus_Pa);
}

double kink_angle_rad(double mode1_Pa_sqrt_m, double mode2_Pa_sqrt_m) {
  // The root of K_I sin t + K_II (3 cos t - 1) = 0 written without K_II in a denominator,
  // so that pure Mode I gives 0 rather than 0 / 0.
  const double k1 = std::max(mode1_Pa_sqrt_m, 0.0);
  const double denominator = k1 + std::sqrt(k1 * k1 + 8.0 * mode2_Pa_sqrt_m * mode2_Pa_sqrt_m);
  if (denominator == 0.0) return 0.0;
  return 2.0 * std::atan(-2.0 * mode2_Pa_sqrt_m / denominator);
}

int nearest_direction(const std::vector<Vec2>& directions, const Vec2& crack_direction, double kink_rad) {
  const Vec2 target = Eigen::Rotation2Dd(kink_rad) * crack_direction.normalized();
  int best = -1;
  double best_cosine = -std::numeric_limits<double>::infinity();
  for (int i = 0; i < static_cast<int>(directions.size()); ++i) {
    const double cosine = directions[i].normalized().dot(target);
    if (cosine > best_cosine) best = i, best_cosine = cosine;
  }
  return best;
}

namespace {

/// The tip with every force and opening at w along the line from `a` (w = 0) to `b` (w = 1).
CrackTip interpolated(const CrackTip& a, const CrackTip& b, double w) {
  auto at = [w](double x, double y) { return x + w * (y - x); };
  CrackTip t = b;
  t.tip_normal_N = at(a.tip_normal_N, b.tip_normal_N);
  t.tip_shear_N = at(a.tip_shear_N, b.tip_shear_N);
  t.far_normal_N = at(a.far_normal_N, b.far_normal_N);
  t.far_shear_N = at(a.far_shear_N, b.far_shear_N);
  t.far_opening_m = at(a.far_opening_m, b.far_opening_m);
  t.far_slip_m = at(a.far_slip_m, b.far_slip_m);
  t.near_opening_m = at(a.near_opening_m, b.near_opening_m);
  t.near_slip_m = at(a.near_slip_m, b.near_slip_m);
  t.second_opening_m = at(a.second_opening_m, b.second_opening_m);
  t.second_slip_m = at(a.second_slip_m, b.second_slip_m);
  return t;
}

}  // namespace

double level_at_critical_ratio(double level_a, const CrackTip& tip_a, double level_b, const CrackTip& tip_b,
                               const Toughness& toughness) {
  constexpr double kNever = std::numeric_limits<double>::infinity();
  if (level_b == level_a) return kNever;
  // In w = (level - level_b) / (level_b - level_a) every force and opening is linear, so
  // the ratio is a quadratic r(w) = p w^2 + q w + r0, fixed by its values at w = -1, 0, 1.
  const double r0 = mixed_mode_ratio(tip_b, toughness);
  const double r_minus = mixed_mode_ratio(tip_a, toughness);
  const double r_plus = mixed_mode_ratio(interpolated(tip_a, tip_b, 2.0), toughness);
  const double p = 0.5 * (r_plus + r_minus) - r0;
  const double q = 0.5 * (r_plus - r_minus);
  const double c = r0 - 1.0;
  if (c >= 0.0) return level_b;  // already critical
  // Smallest w > 0 with p w^2 + q w + c = 0 (c < 0).
  double w = kNever;
  if (std::abs(p) <= 1e-12 * (std::abs(q) + std::abs(c))) {
    if (q > 0.0) w = -c / q;
  } else {
    const double discriminant = q * q - 4.0 * p * c;
    if (discriminant >= 0.0) {
      const double root = std::sqrt(discriminant);
      for (double candidate : {(-q - root) / (2.0 * p), (-q + root) / (2.0 * p)})
        if (candidate > 0.0) w = std::min(w, candidate);
    }
  }
  if (!std::isfinite(w)) return kNever;
  // The quadratic knows nothing of the contacts that stop pulling (G_I >= 0 per contact):
  // trust the root only if the tip there is critical indeed. A contact that stops pulling
  // takes its whole share of G; a term of round-off size that changes sign between the
  // two levels (the opening at the tip point itself, 1e-16 to 1e-12 m) moves it by more
  // than 1e-9 (unit test ...IgnoresAnOpeningOfRoundOffSizeAtTheTip), which must not veto
  // the prediction.
  if (mixed_mode_ratio(interpolated(tip_a, tip_b, 1.0 + w), toughness) < 1.0 - 1e-6) return kNever;
  return level_b + w * (level_b - level_a);
}

std::vector<int> critical_tips(const std::vector<double>& ratios) {
  std::vector<int> selected;
  for (int i = 0; i < static_cast<int>(ratios.size()); ++i)
    if (ratios[i] >= 1.0) selected.push_back(i);
  return selected;
}

}  // namespace hfdda::fracture
