#pragma once
// Draws of the case-file keys given as distributions (docs/distributions.md). Following
// the seed's Monte Carlo runs (W. E. Morgan, PhD dissertation, Georgia Institute of
// Technology, 2014, sections 5.5 and 5.6), the far-field stresses, the viscosity and the
// injection rates are drawn once per run, the Young's modulus and Poisson's ratio block
// by block, and the tensile strength, friction angle and hydraulic width joint by joint.
//
// Every key has its own random stream, seeded from the case's `random_seed` and the key's
// name (stochastic::RandomStream), drawn in block or joint order: the same case and seed
// give the same values on every machine, and a key given or removed as a distribution
// leaves the draws of the others unchanged. An ensemble realisation seeds each group of
// keys (parameter_group) on its own, so that a group can be held while others vary.

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "io/case_config.hpp"
#include "stochastic/scalar_distribution.hpp"

namespace hfdda::simulation {

/// What a run drew from one key given as a distribution (summary.json).
struct ParameterDraw {
  std::string key;   ///< case-file key, "joints.tensile_strength"
  std::string law;   ///< "log_triangular(min 5e6, mode 6e6, max 7e6)"
  std::string per;   ///< "run", "block" or "joint"
  int count = 0;     ///< values drawn
  double min = 0.0, mean = 0.0, max = 0.0;  ///< of the values drawn (the value itself for one draw)
};

/// The group of a key for an ensemble (io::EnsembleConfig::resample): "rock" (materials,
/// joints, far_field), "natural_fractures" (fractures, fracture_sets) or "fluid" (fluid,
/// injections). Throws std::invalid_argument for a key of none.
std::string parameter_group(const std::string& key);

/// The streams of the keys of one run, and a summary of what each has drawn.
class ParameterSampler {
 public:
  /// Every key seeded from `random_seed` (the case's own).
  explicit ParameterSampler(std::uint64_t random_seed) : random_seed_(random_seed) {}
  /// The keys of each group seeded from its own seed (a realisation of an ensemble);
  /// every group of parameter_group must be present.
  explicit ParameterSampler(std::map<std::string, std::uint64_t> seed_of_group)
      : seed_of_group_(std::move(seed_of_group)) {}

  /// The next value of `key` from `law` (`per`: "run", "block" or "joint").
  double draw(const std::string& key, const stochastic::ScalarDistribution& law, const std::string& per);

  /// One entry per key drawn, in the order first drawn.
  std::vector<ParameterDraw> draws() const;

 private:
  struct KeyStream {
    stochastic::RandomStream stream;
    ParameterDraw summary;
    double sum = 0.0;
  };
  std::uint64_t seed_of(const std::string& key) const;

  std::uint64_t random_seed_ = 0;
  std::map<std::string, std::uint64_t> seed_of_group_;  ///< empty: random_seed_ for every key
  std::vector<KeyStream> keys_;
  std::map<std::string, std::size_t> index_;
};

/// The case with the keys drawn once per run (far_field.sxx, syy, sxy, fluid.viscosity,
/// injections[].mass_rate) replaced by their draws, as numbers. Keys drawn per block or
/// per joint keep their laws: the model draws them when it is built.
io::CaseConfig draw_run_parameters(const io::CaseConfig& config, ParameterSampler& sampler);

}  // namespace hfdda::simulation
