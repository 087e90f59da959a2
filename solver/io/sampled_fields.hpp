#pragma once
// Keys that take a number or a distribution (docs/distributions.md):
//
//   youngs_modulus: 25e9
//   youngs_modulus: {distribution: triangular, min: 8e9, mode: 10e9, max: 12e9}
//
// The law is kept beside the number in the config struct (the member `<name>_law`); the
// number then holds the law's central value until the model draws the key. A number
// written later in the extends chain removes an inherited law, and the reverse.

#include <optional>
#include <string>
#include <utility>

#include "io/case_config.hpp"
#include "io/case_fields.hpp"
#include "stochastic/scalar_distribution.hpp"

namespace hfdda::io::schema {

/// How often a key given as a distribution is drawn (seed 5.5, Tables 5.5 and 5.6).
enum class SamplingScope {
  realisation,  ///< one value per run
  block,        ///< one value per block of the material zone
  joint,        ///< one value per joint the key applies to
};

/// The sentence the docs add to a key's description.
std::string scope_sentence(SamplingScope scope);

/// The keys of a `{distribution: ...}` map as written; which ones are needed depends on
/// `distribution`.
struct DistributionKeys {
  std::string distribution;
  std::optional<double> min, mode, max, mean, standard_deviation, median, sigma;
};

/// The table of a `{distribution: ...}` map (docs section "Distributions").
const Table<DistributionKeys>& distribution_table();

/// Reads the map `{distribution: ..., ...}` of `key`: exactly the keys of the chosen law,
/// the law's rules (min <= mode <= max, min > 0 for the laws on logarithms, ...), and
/// min and max within `range`, the allowed range of the key. Throws InputError at the
/// offending entry ("joints.tensile_strength.max": "min 5e6 > max 1e6: ...").
stochastic::ScalarDistribution read_distribution(FileReader& r, const YAML::Node& node, const std::string& key,
                                                 const Range& range);

/// `number_or_law` of the field kinds below: refuses what is neither a scalar nor a map.
void check_number_or_map(const FileReader& r, const YAML::Node& node, const std::string& key);

KeyDoc sampled_doc(Doc d, SamplingScope scope, std::string default_text, std::string allowed);

/// Reads a number in `range` into `value` (no law), or a distribution whose values all lie
/// in `range` into `law` with its central value in `value`.
template <class Law>
void read_number_or_law(FileReader& r, const YAML::Node& n, const std::string& key, const Range& range,
                        double& value, Law& law) {
  check_number_or_map(r, n, key);
  if (n.IsMap()) {
    const stochastic::ScalarDistribution distribution = read_distribution(r, n, key, range);
    value = distribution.central_value();
    law = distribution;
    return;
  }
  value = read_number(r, n, key);
  check_range(r, n, key, range, value);
  law.reset();
}

/// A number in `range`, or a distribution whose values all lie in `range`.
template <class T>
Field<T> sampled_number(Doc d, double T::*member, ParameterLaw T::*law, Range range, SamplingScope scope,
                        std::string also = "") {
  auto read = [member, law, range](FileReader& r, const YAML::Node& n, const std::string& key, T& out) {
    read_number_or_law(r, n, key, range, out.*member, out.*law);
  };
  const std::string allowed = also.empty() ? range.text() : range.text() + ", " + also;
  return {sampled_doc(std::move(d), scope, format_number(T{}.*member), allowed), read};
}

/// As sampled_number, for a key that, when absent, is taken from elsewhere (`fallback`).
template <class T>
Field<T> optional_sampled_number(Doc d, std::optional<double> T::*member, ParameterLaw T::*law, Range range,
                                 std::string fallback, SamplingScope scope) {
  auto read = [member, law, range](FileReader& r, const YAML::Node& n, const std::string& key, T& out) {
    if (n.IsNull()) {
      (out.*member).reset();
      (out.*law).reset();
      return;
    }
    double value = 0.0;
    read_number_or_law(r, n, key, range, value, out.*law);
    out.*member = value;
  };
  return {sampled_doc(std::move(d), scope, std::move(fallback), range.text()), read};
}

}  // namespace hfdda::io::schema
