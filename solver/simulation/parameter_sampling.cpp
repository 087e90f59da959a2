// Draws of the case-file keys given as distributions (parameter_sampling.hpp).

#include "simulation/parameter_sampling.hpp"

#include <algorithm>
#include <stdexcept>

namespace hfdda::simulation {

std::string parameter_group(const std::string& key) {
  const auto starts = [&](const char* prefix) { return key.rfind(prefix, 0) == 0; };
  if (starts("materials[") || starts("joints.") || starts("far_field.")) return "rock";
  if (starts("fractures[") || starts("fracture_sets[")) return "natural_fractures";
  if (starts("fluid.") || starts("injections[")) return "fluid";
  throw std::invalid_argument("parameter_group: key '" + key + "' belongs to no group");
}

std::uint64_t ParameterSampler::seed_of(const std::string& key) const {
  if (seed_of_group_.empty()) return random_seed_;
  const std::string group = parameter_group(key);
  const auto it = seed_of_group_.find(group);
  if (it == seed_of_group_.end())
    throw std::invalid_argument("ParameterSampler: no seed for group '" + group + "' of key '" + key + "'");
  return it->second;
}

double ParameterSampler::draw(const std::string& key, const stochastic::ScalarDistribution& law,
                              const std::string& per) {
  auto it = index_.find(key);
  if (it == index_.end()) {
    ParameterDraw summary;
    summary.key = key;
    summary.law = law.text();
    summary.per = per;
    keys_.push_back(KeyStream{stochastic::RandomStream(seed_of(key), key), summary, 0.0});
    it = index_.emplace(key, keys_.size() - 1).first;
  }
  KeyStream& k = keys_[it->second];
  const double value = law.sample(k.stream.get());
  ParameterDraw& s = k.summary;
  s.min = s.count == 0 ? value : std::min(s.min, value);
  s.max = s.count == 0 ? value : std::max(s.max, value);
  ++s.count;
  k.sum += value;
  s.mean = k.sum / s.count;
  return value;
}

std::vector<ParameterDraw> ParameterSampler::draws() const {
  std::vector<ParameterDraw> all;
  for (const KeyStream& k : keys_) all.push_back(k.summary);
  return all;
}

namespace {

/// Replaces `value` by a draw of `law` under `key`, once per run.
void draw_once(ParameterSampler& sampler, const std::string& key, double& value, io::ParameterLaw& law) {
  if (!law) return;
  value = sampler.draw(key, *law, "run");
  law.reset();
}

}  // namespace

io::CaseConfig draw_run_parameters(const io::CaseConfig& config, ParameterSampler& sampler) {
  io::CaseConfig c = config;
  // Seed 5.6: triangular laws of the largest and smallest compressive stress.
  draw_once(sampler, "far_field.sxx", c.far_field.sxx_Pa, c.far_field.sxx_law);
  draw_once(sampler, "far_field.syy", c.far_field.syy_Pa, c.far_field.syy_law);
  draw_once(sampler, "far_field.sxy", c.far_field.sxy_Pa, c.far_field.sxy_law);
  // Seed 5.5: the fluid design parameters, "sampled individually for each realization".
  if (c.fluid) draw_once(sampler, "fluid.viscosity", c.fluid->viscosity_Pa_s, c.fluid->viscosity_law);
  for (std::size_t i = 0; i < c.injections.size(); ++i)
    draw_once(sampler, "injections[" + std::to_string(i) + "].mass_rate", c.injections[i].mass_rate_kg_s,
              c.injections[i].mass_rate_law);
  return c;
}

}  // namespace hfdda::simulation
