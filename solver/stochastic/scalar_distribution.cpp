// Scalar probability laws (scalar_distribution.hpp); formulas in docs/distributions.md.

#include "stochastic/scalar_distribution.hpp"

#include "core/number_text.hpp"

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_randist.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <new>
#include <vector>

namespace hfdda::stochastic {

namespace {

/// Truncation bounds further than this many standard deviations from the mean hold a
/// probability the normal CDF cannot resolve in double precision (Q(38) underflows).
constexpr double kMaxTruncationDeviations = 30.0;


bool has_bounds(DistributionKind k) { return k != DistributionKind::constant && k != DistributionKind::lognormal; }

bool on_logarithms(DistributionKind k) {
  return k == DistributionKind::log_triangular || k == DistributionKind::truncated_lognormal ||
         k == DistributionKind::power_law;
}

double triangular_cdf(double min, double mode, double max, double x) {
  if (x <= min) return max <= min && x == min ? 1.0 : 0.0;
  if (x >= max) return 1.0;
  if (x <= mode) return (x - min) * (x - min) / ((max - min) * (mode - min));
  return 1.0 - (max - x) * (max - x) / ((max - min) * (max - mode));
}

// The standard normal restricted to [a, b]: computed with the upper-tail function Q when
// the whole interval lies above the mean, so that neither the draw nor the CDF loses its
// digits to 1 - P in the tail.

double truncated_standard_normal_quantile(double a, double b, double u) {
  if (a > 0.0) {
    const double qa = gsl_cdf_ugaussian_Q(a), qb = gsl_cdf_ugaussian_Q(b);
    return gsl_cdf_ugaussian_Qinv(qa - u * (qa - qb));
  }
  const double pa = gsl_cdf_ugaussian_P(a), pb = gsl_cdf_ugaussian_P(b);
  return gsl_cdf_ugaussian_Pinv(pa + u * (pb - pa));
}

double truncated_standard_normal_cdf(double a, double b, double z) {
  if (z <= a) return b <= a && z == a ? 1.0 : 0.0;
  if (z >= b) return 1.0;
  if (a > 0.0) {
    const double qa = gsl_cdf_ugaussian_Q(a);
    return std::clamp((qa - gsl_cdf_ugaussian_Q(z)) / (qa - gsl_cdf_ugaussian_Q(b)), 0.0, 1.0);
  }
  const double pa = gsl_cdf_ugaussian_P(a);
  return std::clamp((gsl_cdf_ugaussian_P(z) - pa) / (gsl_cdf_ugaussian_P(b) - pa), 0.0, 1.0);
}

/// The normal N(centre, spread^2) restricted to [lo, hi], as (a, b) in standard units.
struct StandardBounds {
  double a, b;
};
StandardBounds standard_bounds(double centre, double spread, double lo, double hi) {
  return {(lo - centre) / spread, (hi - centre) / spread};
}

}  // namespace

std::string kind_name(DistributionKind kind) {
  switch (kind) {
    case DistributionKind::constant: return "constant";
    case DistributionKind::uniform: return "uniform";
    case DistributionKind::triangular: return "triangular";
    case DistributionKind::log_triangular: return "log_triangular";
    case DistributionKind::truncated_normal: return "truncated_normal";
    case DistributionKind::truncated_lognormal: return "truncated_lognormal";
    case DistributionKind::lognormal: return "lognormal";
    case DistributionKind::power_law: return "power_law";
  }
  return "unknown";
}

// ---------------------------------------------------------------------------
// Construction and validation

ScalarDistribution ScalarDistribution::constant(double value) {
  ScalarDistribution d;
  d.kind = DistributionKind::constant;
  d.value = value;
  return d;
}

ScalarDistribution ScalarDistribution::uniform(double min, double max) {
  ScalarDistribution d;
  d.kind = DistributionKind::uniform;
  d.min = min;
  d.max = max;
  return d;
}

ScalarDistribution ScalarDistribution::triangular(double min, double mode, double max) {
  ScalarDistribution d = uniform(min, max);
  d.kind = DistributionKind::triangular;
  d.mode = mode;
  return d;
}

ScalarDistribution ScalarDistribution::log_triangular(double min, double mode, double max) {
  ScalarDistribution d = triangular(min, mode, max);
  d.kind = DistributionKind::log_triangular;
  return d;
}

ScalarDistribution ScalarDistribution::truncated_normal(double mean, double standard_deviation, double min,
                                                        double max) {
  ScalarDistribution d = uniform(min, max);
  d.kind = DistributionKind::truncated_normal;
  d.mean = mean;
  d.standard_deviation = standard_deviation;
  return d;
}

ScalarDistribution ScalarDistribution::truncated_lognormal(double median, double sigma, double min, double max) {
  ScalarDistribution d = uniform(min, max);
  d.kind = DistributionKind::truncated_lognormal;
  d.median = median;
  d.sigma = sigma;
  return d;
}

ScalarDistribution ScalarDistribution::lognormal(double median, double sigma) {
  ScalarDistribution d;
  d.kind = DistributionKind::lognormal;
  d.median = median;
  d.sigma = sigma;
  return d;
}

ScalarDistribution ScalarDistribution::power_law(double exponent, double min, double max) {
  ScalarDistribution d = uniform(min, max);
  d.kind = DistributionKind::power_law;
  d.exponent = exponent;
  return d;
}

std::optional<DistributionError> ScalarDistribution::validate() const {
  using K = DistributionKind;
  // The parameters of this kind, in the order they are written.
  std::vector<std::pair<const char*, double>> used;
  switch (kind) {
    case K::constant: used = {{"value", value}}; break;
    case K::uniform: used = {{"min", min}, {"max", max}}; break;
    case K::triangular:
    case K::log_triangular: used = {{"min", min}, {"mode", mode}, {"max", max}}; break;
    case K::truncated_normal: used = {{"mean", mean}, {"std", standard_deviation}, {"min", min}, {"max", max}}; break;
    case K::truncated_lognormal: used = {{"median", median}, {"sigma", sigma}, {"min", min}, {"max", max}}; break;
    case K::lognormal: used = {{"median", median}, {"sigma", sigma}}; break;
    case K::power_law: used = {{"exponent", exponent}, {"min", min}, {"max", max}}; break;
  }
  for (const auto& [name, v] : used)
    if (!std::isfinite(v)) return DistributionError{name, "must be a finite number (got " + number_text(v) + ")"};
  const std::string law = kind_name(kind);
  if (has_bounds(kind) && min > max)
    return DistributionError{"max", "min " + number_text(min) + " > max " + number_text(max) +
                                        ": min must be <= max (swapped?)"};
  if (on_logarithms(kind) && !(min > 0.0))
    return DistributionError{"min", "must be > 0: " + law + " is a law of the logarithm of the value (got " +
                                        number_text(min) + ")"};
  if ((kind == K::triangular || kind == K::log_triangular) && !(mode >= min && mode <= max))
    return DistributionError{"mode", "mode " + number_text(mode) + " lies outside [min, max] = [" + number_text(min) +
                                         ", " + number_text(max) + "]"};
  if (kind == K::truncated_normal && !(standard_deviation > 0.0))
    return DistributionError{"std", "must be > 0 (got " + number_text(standard_deviation) + ")"};
  if (kind == K::truncated_lognormal || kind == K::lognormal) {
    if (!(median > 0.0)) return DistributionError{"median", "must be > 0 (got " + number_text(median) + ")"};
    if (!(sigma > 0.0)) return DistributionError{"sigma", "must be > 0 (got " + number_text(sigma) + ")"};
  }
  if ((kind == K::truncated_normal || kind == K::truncated_lognormal) && min < max) {
    const bool logs = kind == K::truncated_lognormal;
    const StandardBounds s = logs ? standard_bounds(std::log(median), sigma, std::log(min), std::log(max))
                                  : standard_bounds(mean, standard_deviation, min, max);
    if (s.a > kMaxTruncationDeviations || s.b < -kMaxTruncationDeviations)
      return DistributionError{s.a > kMaxTruncationDeviations ? "min" : "max",
                               "[min, max] = [" + number_text(min) + ", " + number_text(max) + "] lies more than " +
                                   number_text(kMaxTruncationDeviations) + " standard deviations from the " +
                                   (logs ? "median (on ln)" : "mean") +
                                   ", where the normal law holds no probability a double can resolve"};
  }
  return std::nullopt;
}

// ---------------------------------------------------------------------------
// Sampling and CDF

double triangular_quantile(double min, double mode, double max, double u) {
  const double a = min, b = max, c = mode;
  if (b <= a) return a;
  if (u < (c - a) / (b - a)) return a + std::sqrt(u * (b - a) * (c - a));
  return b - std::sqrt((1.0 - u) * (b - a) * (b - c));
}

// Written in t = x / min with expm1 and log1p, so that neither a tiny min nor an exponent
// near 1 loses the result to overflow or cancellation.
double power_law_quantile(double exponent, double min, double max, double u) {
  const double lo = min, hi = max, k = 1.0 - exponent;
  if (hi <= lo) return lo;
  const double log_r = std::log(hi / lo);
  if (std::abs(k * log_r) < 1e-12) return std::clamp(lo * std::exp(u * log_r), lo, hi);
  return std::clamp(lo * std::exp(std::log1p(u * std::expm1(k * log_r)) / k), lo, hi);
}

double ScalarDistribution::sample(gsl_rng* generator) const {
  using K = DistributionKind;
  switch (kind) {
    case K::constant: return value;
    case K::uniform: return gsl_ran_flat(generator, min, max);
    case K::triangular: return triangular_quantile(min, mode, max, gsl_rng_uniform(generator));
    case K::log_triangular: {  // seed 5.5: triangular on log10 of the value
      const double u = gsl_rng_uniform(generator);
      const double y = triangular_quantile(std::log10(min), std::log10(mode), std::log10(max), u);
      return std::clamp(std::pow(10.0, y), min, max);
    }
    case K::truncated_normal: {
      const double u = gsl_rng_uniform(generator);
      if (max <= min) return min;
      const StandardBounds s = standard_bounds(mean, standard_deviation, min, max);
      return std::clamp(mean + standard_deviation * truncated_standard_normal_quantile(s.a, s.b, u), min, max);
    }
    case K::truncated_lognormal: {
      const double u = gsl_rng_uniform(generator);
      if (max <= min) return min;
      const double mu = std::log(median);
      const StandardBounds s = standard_bounds(mu, sigma, std::log(min), std::log(max));
      return std::clamp(std::exp(mu + sigma * truncated_standard_normal_quantile(s.a, s.b, u)), min, max);
    }
    case K::lognormal: return gsl_ran_lognormal(generator, std::log(median), sigma);
    case K::power_law: return power_law_quantile(exponent, min, max, gsl_rng_uniform(generator));
  }
  return value;
}

double ScalarDistribution::cdf(double x) const {
  using K = DistributionKind;
  switch (kind) {
    case K::constant: return x >= value ? 1.0 : 0.0;
    case K::uniform:
      if (max <= min) return x >= min ? 1.0 : 0.0;
      return gsl_cdf_flat_P(x, min, max);
    case K::triangular: return triangular_cdf(min, mode, max, x);
    case K::log_triangular:
      if (x <= 0.0) return 0.0;
      return triangular_cdf(std::log10(min), std::log10(mode), std::log10(max), std::log10(x));
    case K::truncated_normal: {
      if (max <= min) return x >= min ? 1.0 : 0.0;
      const StandardBounds s = standard_bounds(mean, standard_deviation, min, max);
      return truncated_standard_normal_cdf(s.a, s.b, (x - mean) / standard_deviation);
    }
    case K::truncated_lognormal: {
      if (max <= min) return x >= min ? 1.0 : 0.0;
      if (x <= 0.0) return 0.0;
      const double mu = std::log(median);
      const StandardBounds s = standard_bounds(mu, sigma, std::log(min), std::log(max));
      return truncated_standard_normal_cdf(s.a, s.b, (std::log(x) - mu) / sigma);
    }
    case K::lognormal: return x <= 0.0 ? 0.0 : gsl_cdf_lognormal_P(x, std::log(median), sigma);
    case K::power_law: {
      if (x < min) return 0.0;
      if (x >= max) return 1.0;
      const double k = 1.0 - exponent, log_t = std::log(x / min), log_r = std::log(max / min);
      if (std::abs(k * log_r) < 1e-12) return log_t / log_r;
      return std::expm1(k * log_t) / std::expm1(k * log_r);
    }
  }
  return 0.0;
}

double ScalarDistribution::lowest() const {
  if (kind == DistributionKind::constant) return value;
  if (kind == DistributionKind::lognormal) return 0.0;
  return min;
}

double ScalarDistribution::highest() const {
  if (kind == DistributionKind::constant) return value;
  if (kind == DistributionKind::lognormal) return std::numeric_limits<double>::infinity();
  return max;
}

double ScalarDistribution::central_value() const {
  using K = DistributionKind;
  switch (kind) {
    case K::constant: return value;
    case K::uniform: return 0.5 * (min + max);
    case K::triangular:
    case K::log_triangular: return mode;
    case K::truncated_normal: return std::clamp(mean, min, std::max(min, max));
    case K::truncated_lognormal: return std::clamp(median, min, std::max(min, max));
    case K::lognormal: return median;
    case K::power_law: return min;
  }
  return value;
}

std::string ScalarDistribution::text() const {
  using K = DistributionKind;
  const auto p = [](const char* name, double v) { return std::string(name) + " " + number_text(v); };
  std::string parameters;
  switch (kind) {
    case K::constant: parameters = number_text(value); break;
    case K::uniform: parameters = p("min", min) + ", " + p("max", max); break;
    case K::triangular:
    case K::log_triangular: parameters = p("min", min) + ", " + p("mode", mode) + ", " + p("max", max); break;
    case K::truncated_normal:
      parameters = p("mean", mean) + ", " + p("std", standard_deviation) + ", " + p("min", min) + ", " + p("max", max);
      break;
    case K::truncated_lognormal:
      parameters = p("median", median) + ", " + p("sigma", sigma) + ", " + p("min", min) + ", " + p("max", max);
      break;
    case K::lognormal: parameters = p("median", median) + ", " + p("sigma", sigma); break;
    case K::power_law: parameters = p("exponent", exponent) + ", " + p("min", min) + ", " + p("max", max); break;
  }
  return kind_name(kind) + "(" + parameters + ")";
}

// ---------------------------------------------------------------------------
// Streams

unsigned long stream_seed(std::uint64_t seed, const std::string& name) {
  std::uint64_t name_hash = 14695981039346656037ull;  // FNV-1a
  for (const char ch : name) {
    name_hash ^= static_cast<unsigned char>(ch);
    name_hash *= 1099511628211ull;
  }
  std::uint64_t z = seed * 0x9E3779B97F4A7C15ull + name_hash;  // splitmix64
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return static_cast<unsigned long>(z & 0xFFFFFFFFull);  // GSL's mt19937 uses 32 bits of its seed
}

RandomStream::RandomStream(std::uint64_t seed, const std::string& name)
    : generator_(gsl_rng_alloc(gsl_rng_mt19937)) {
  if (!generator_) throw std::bad_alloc();
  gsl_rng_set(generator_.get(), stream_seed(seed, name));
}

}  // namespace hfdda::stochastic
