// Keys that take a number or a distribution (sampled_fields.hpp).

#include "io/sampled_fields.hpp"

#include <algorithm>
#include <map>
#include <vector>

namespace hfdda::io::schema {

namespace {

using stochastic::ScalarDistribution;

/// The keys each law takes, in the order they are named in messages.
const std::map<std::string, std::vector<std::string>>& law_keys() {
  static const std::map<std::string, std::vector<std::string>> keys{
      {"uniform", {"min", "max"}},
      {"triangular", {"min", "mode", "max"}},
      {"log_triangular", {"min", "mode", "max"}},
      {"truncated_normal", {"mean", "std", "min", "max"}},
      {"truncated_lognormal", {"median", "sigma", "min", "max"}}};
  return keys;
}

/// Exactly the keys of the chosen law.
void check_law_keys(const FileReader& r, const YAML::Node& map, const std::string& key, const std::string& law,
                    const std::set<std::string>& seen) {
  const std::vector<std::string>& wanted = law_keys().at(law);
  const std::string takes = "distribution " + law + " takes " + join(wanted, ", ");
  for (const std::string& name : seen)
    if (name != "distribution" && std::find(wanted.begin(), wanted.end(), name) == wanted.end())
      r.fail(map[name], child_key(key, name), "is not used by " + takes);
  for (const std::string& name : wanted)
    if (!seen.contains(name)) r.fail(map, child_key(key, name), "is required: " + takes);
}

ScalarDistribution law_of(const DistributionKeys& k) {
  const std::string& law = k.distribution;
  if (law == "uniform") return ScalarDistribution::uniform(*k.min, *k.max);
  if (law == "triangular") return ScalarDistribution::triangular(*k.min, *k.mode, *k.max);
  if (law == "log_triangular") return ScalarDistribution::log_triangular(*k.min, *k.mode, *k.max);
  if (law == "truncated_normal")
    return ScalarDistribution::truncated_normal(*k.mean, *k.standard_deviation, *k.min, *k.max);
  return ScalarDistribution::truncated_lognormal(*k.median, *k.sigma, *k.min, *k.max);
}

}  // namespace

std::string scope_sentence(SamplingScope scope) {
  switch (scope) {
    case SamplingScope::realisation: return "A distribution is drawn once per run.";
    case SamplingScope::block: return "A distribution is drawn block by block: one value for each block of the zone.";
    case SamplingScope::joint: return "A distribution is drawn joint by joint: one value for each joint it applies to.";
  }
  return "";
}

const Table<DistributionKeys>& distribution_table() {
  using K = DistributionKeys;
  static const Table<K> table{
      "Distributions (`{distribution: ...}` maps)",
      "A key whose type is `number or distribution` takes a number or a map naming a law and exactly its "
      "parameters, in the key's own unit (sigma: none): `uniform` `min`, `max`; `triangular` `min`, `mode`, "
      "`max`; `log_triangular` the same, the law being triangular on log10 of the value; `truncated_normal` "
      "`mean`, `std` (of the normal before truncation), `min`, `max`; `truncated_lognormal` `median`, `sigma` "
      "(ln X normal with mean ln(median) and standard deviation sigma before truncation), `min`, `max`. "
      "min <= mode <= max (a swapped min and max is an error naming both); min > 0 for `log_triangular` and "
      "`truncated_lognormal`; `min` and `max` within the key's own allowed range; a truncated law's [min, max] "
      "within 30 standard deviations of its mean (or of ln(median)). Each key says whether it is drawn once "
      "per run, block by block or joint by joint; the draws follow from `random_seed` and the key's name and "
      "are listed in the run's summary.json. Formulas and the seed's use of them: docs/distributions.md.",
      {required(choice({"distribution", "",
                        "§5.5: triangular; triangular on log10 for strengths and widths (Tables 5.5, 5.6)",
                        "the law"},
                       &K::distribution,
                       Choices<std::string>{{"uniform", "uniform"},
                                            {"triangular", "triangular"},
                                            {"log_triangular", "log_triangular"},
                                            {"truncated_normal", "truncated_normal"},
                                            {"truncated_lognormal", "truncated_lognormal"}})),
       optional_number({"min", "as the key", "Tables 5.5, 5.6: Min", "smallest value"}, &K::min, any_value(),
                       "none"),
       optional_number({"mode", "as the key", "Tables 5.5, 5.6: Mode",
                        "(log_)triangular: the most likely value"},
                       &K::mode, any_value(), "none"),
       optional_number({"max", "as the key", "Tables 5.5, 5.6: Max", "largest value"}, &K::max, any_value(),
                       "none"),
       optional_number({"mean", "as the key", "", "truncated_normal: mean of the normal before truncation"},
                       &K::mean, any_value(), "none"),
       optional_number({"std", "as the key", "",
                        "truncated_normal: standard deviation of the normal before truncation"},
                       &K::standard_deviation, greater_than(0), "none"),
       optional_number({"median", "as the key", "",
                        "truncated_lognormal: exp of the mean of ln X before truncation"},
                       &K::median, greater_than(0), "none"),
       optional_number({"sigma", "-", "",
                        "truncated_lognormal: standard deviation of ln X before truncation"},
                       &K::sigma, greater_than(0), "none")}};
  return table;
}

void check_number_or_map(const FileReader& r, const YAML::Node& node, const std::string& key) {
  if (!node.IsScalar() && !node.IsMap())
    r.fail(node, key, "expected a number or a distribution map {distribution: ..., ...} (got " + describe(node) + ")");
}

ScalarDistribution read_distribution(FileReader& r, const YAML::Node& node, const std::string& key,
                                     const Range& range) {
  DistributionKeys keys;
  r.forget(key + ".");
  const std::set<std::string> seen = parse_map(r, node, key, distribution_table(), keys);
  check_law_keys(r, node, key, keys.distribution, seen);
  const ScalarDistribution law = law_of(keys);
  if (const auto error = law.validate()) r.fail(node[error->parameter], child_key(key, error->parameter), error->rule);
  for (const auto& [name, bound] : {std::pair<const char*, double>{"min", law.min}, {"max", law.max}})
    if (!range.contains(bound))
      r.fail(node[name], child_key(key, name),
             "must be " + range.rule() + ", the allowed range of the key itself (got " + format_number(bound) + ")");
  return law;
}

KeyDoc sampled_doc(Doc d, SamplingScope scope, std::string default_text, std::string allowed) {
  d.description += ". " + scope_sentence(scope);
  KeyDoc doc = key_doc(d, "number or distribution", std::move(default_text), std::move(allowed));
  doc.child = [] { return section_doc(distribution_table()); };
  return doc;
}

}  // namespace hfdda::io::schema
