#pragma once
// Probability laws of scalar parameters, sampled with a GSL generator the caller passes
// in (there is no global generator): the same generator state gives the same value on
// every machine. One implementation serves the case-file keys given as distributions
// and the target lengths of generated fracture sets.
//
// The seed draws the Young's modulus, Poisson's ratio and friction angles from triangular
// laws, and tensile strengths and natural-fracture widths from triangular laws on log10 of
// the value, "as these parameters can vary over orders of magnitude" (W. E. Morgan, PhD
// dissertation, Georgia Institute of Technology, 2014, section 5.5, Tables 5.5 and 5.6);
// section 5.3 draws fracture lengths (uniform, "though any distribution may be
// assigned"). Formulas and parameters: docs/distributions.md.

#include <gsl/gsl_rng.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

namespace hfdda::stochastic {

enum class DistributionKind {
  constant,             ///< always `value`
  uniform,              ///< flat on [min, max]
  triangular,           ///< rises linearly from min to mode, falls linearly to max
  log_triangular,       ///< log10 X triangular on [log10 min, log10 max] with mode log10 mode; min > 0
  truncated_normal,     ///< N(mean, std^2) restricted to [min, max]
  truncated_lognormal,  ///< ln X ~ N(ln median, sigma^2) restricted to [min, max]; min > 0
  lognormal,            ///< ln X ~ N(ln median, sigma^2), not truncated (fracture lengths)
  power_law,            ///< density proportional to x^-exponent on [min, max]; min > 0 (fracture lengths)
};

/// The name of a kind as written in case files ("log_triangular").
std::string kind_name(DistributionKind kind);

/// A parameter of a law that breaks a rule, and the rule ("min 5e6 > max 1e6: ...").
struct DistributionError {
  std::string parameter;  ///< "min", "mode", "max", "mean", "std", "median", "sigma", "exponent" or "value"
  std::string rule;
};

/// A scalar law. Parameters are in the units of the quantity drawn (sigma and exponent
/// are dimensionless); only those of `kind` are used. Build one with the named
/// constructors, check it with validate() before sampling.
struct ScalarDistribution {
  DistributionKind kind = DistributionKind::constant;
  double value = 0.0;               ///< constant
  double min = 0.0, max = 0.0;      ///< bounds of every law but constant and lognormal
  double mode = 0.0;                ///< triangular, log_triangular: the most likely value
  double mean = 0.0;                ///< truncated_normal: mean of the normal before truncation
  double standard_deviation = 0.0;  ///< truncated_normal: of the normal before truncation
  double median = 0.0;              ///< (truncated_)lognormal: exp of the mean of ln X before truncation
  double sigma = 0.0;               ///< (truncated_)lognormal: standard deviation of ln X before truncation
  double exponent = 0.0;            ///< power_law: a of the density x^-a

  static ScalarDistribution constant(double value);
  static ScalarDistribution uniform(double min, double max);
  static ScalarDistribution triangular(double min, double mode, double max);
  static ScalarDistribution log_triangular(double min, double mode, double max);
  static ScalarDistribution truncated_normal(double mean, double standard_deviation, double min, double max);
  static ScalarDistribution truncated_lognormal(double median, double sigma, double min, double max);
  static ScalarDistribution lognormal(double median, double sigma);
  static ScalarDistribution power_law(double exponent, double min, double max);

  /// The first rule the parameters break, if any: finite parameters, min <= max,
  /// min <= mode <= max, min > 0 for the laws on logarithms, std and sigma > 0, and a
  /// truncation interval within 30 standard deviations of the mean.
  std::optional<DistributionError> validate() const;

  /// One value drawn with `generator` (not owned; constant draws nothing). Uses one
  /// uniform number per value, except lognormal (GSL's Gaussian sampler); the result
  /// lies in [lowest(), highest()].
  double sample(gsl_rng* generator) const;

  /// P(X <= x).
  double cdf(double x) const;

  /// Smallest and largest value the law can give (lognormal: 0 and +infinity).
  double lowest() const;
  double highest() const;

  /// A value that stands for the law where one number is needed before any draw: the
  /// constant, the middle of a uniform law, the mode of a triangular one, the mean or
  /// median moved into [min, max] for the normal laws, min for a power law.
  double central_value() const;

  /// "triangular(min 8e9, mode 1e10, max 1.2e10)".
  std::string text() const;
};

/// Inverse CDF of the triangular law on [min, max] with mode `mode`, at u in [0, 1]
/// (GSL has no triangular sampler). Returns min when max <= min.
double triangular_quantile(double min, double mode, double max, double u);

/// Inverse CDF of the density proportional to x^-exponent on [min, max] (GSL's Pareto
/// law is not truncated), at u in [0, 1]. Returns min when max <= min.
double power_law_quantile(double exponent, double min, double max, double u);

/// The seed of the stream named `name` of a run seeded with `seed`: FNV-1a of the name,
/// mixed with the seed by splitmix64, cut to the 32 bits GSL's mt19937 uses. Neighbouring
/// seeds and similar names give unrelated streams.
unsigned long stream_seed(std::uint64_t seed, const std::string& name);

/// A GSL mt19937 generator seeded with stream_seed(seed, name), freed with the object:
/// each quantity drawn has its own stream, so adding or removing one leaves the draws of
/// the others unchanged.
class RandomStream {
 public:
  RandomStream(std::uint64_t seed, const std::string& name);
  gsl_rng* get() const { return generator_.get(); }

 private:
  struct Free {
    void operator()(gsl_rng* r) const { gsl_rng_free(r); }
  };
  std::unique_ptr<gsl_rng, Free> generator_;
};

}  // namespace hfdda::stochastic
