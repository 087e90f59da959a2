#pragma once
// Mutations of case files for the fuzz driver: byte, line and splice edits, numbers
// swapped for extreme values, YAML constructs the reader must refuse or survive, and
// truncation, stacked several at a time.
//
// Input i of a run is made from (seed, i) alone, so any input can be made again without
// the ones before it. The random numbers come from SplitMix64 and our own range
// reduction, not <random>'s distributions, so inputs are the same with every compiler
// and standard library.

#include <cstdint>
#include <string>
#include <vector>

namespace hfdda::fuzz {

/// SplitMix64 (Steele, Lea, Flood 2014): tiny, fast and good enough to pick mutations.
class Rng {
 public:
  explicit Rng(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next();
  /// Uniform in [0, n) (n > 0).
  std::size_t below(std::size_t n) { return static_cast<std::size_t>(next() % n); }
  bool chance(double p) { return static_cast<double>(next() >> 11) * 0x1p-53 < p; }

 private:
  std::uint64_t state_;
};

/// The generator of input `index` of a run with `seed`.
Rng input_rng(std::uint64_t seed, std::uint64_t index);

class CaseMutator {
 public:
  /// `seeds`: the texts mutated (at least one). Their words (keys and word values)
  /// become the dictionary of the word-replacing mutation.
  explicit CaseMutator(std::vector<std::string> seeds);

  /// A mutated copy of a randomly chosen seed; the names of the mutations applied, in
  /// order, are appended to `applied` when it is given.
  std::string make_input(Rng& rng, std::vector<std::string>* applied = nullptr) const;

  /// One mutation of `text`; returns its name.
  std::string mutate_once(std::string& text, Rng& rng) const;

  const std::vector<std::string>& seeds() const { return seeds_; }

  /// Inputs are cut to this size: bigger ones only make the run slower.
  static constexpr std::size_t kMaxInputBytes = 64 * 1024;

 private:
  std::vector<std::string> seeds_;
  std::vector<std::string> words_;
};

}  // namespace hfdda::fuzz
