#pragma once
// The function the fuzzers drive: bytes in, a case file read (and, when cheap, its model
// built, as `hfdda check` does), and the contract of the reader checked.
//
// Contract: the reader returns a CaseConfig or throws InputError whose what() is
// non-empty and short (values it echoes are clipped), with a key and a line >= 0. A
// config it accepts keeps the invariants the solver relies on. Building the model may
// also throw InputError or ModelError, under the same limits. Anything else (another
// exception type, a broken invariant) is a finding; crashes, sanitizer reports and
// hangs are findings the caller sees.

#include <cstddef>
#include <string>
#include <string_view>

#include "io/case_config.hpp"

namespace hfdda::fuzz {

/// Label of every input in messages: a file in a directory that does not exist, so an
/// `extends:` with a relative path fails the same way wherever the fuzzer runs.
inline constexpr std::string_view kInputLabel = "/hfdda-fuzz-input/case.yaml";

struct TargetOptions {
  /// Build the model of an accepted case when its estimated block count is at most this
  /// (0: never); larger meshes would take far longer than the reading itself.
  double max_model_blocks = 2000;
  /// Longest acceptable what() of an error: echoed values are clipped by the reader.
  std::size_t max_message_chars = 2000;
};

enum class Outcome { accepted, refused, finding };

struct TargetResult {
  Outcome outcome = Outcome::accepted;
  std::string stage;  ///< "read" or "model": where the input was refused or the finding made
  std::string key;    ///< refused: key of the InputError ("(model)" for a ModelError)
  std::string rule;   ///< refused: rule of the InputError; finding: what broke the contract
  int line = 0;       ///< refused: line of the InputError
  bool model_built = false;
  /// accepted: the model was not built because the input would hit a known problem of
  /// the solver (known_problem()); what it is.
  std::string known_problem;
};

/// Runs one input through the reader (and the model builder when cheap).
TargetResult run_case_reader(std::string_view bytes, const TargetOptions& options = {});

/// Rough number of blocks the mesh of `config` would have (cheap: no mesh is built).
double estimated_block_count(const io::CaseConfig& config);

/// Empty when an accepted config keeps the invariants the reader promises; otherwise
/// the first one it breaks.
std::string broken_invariant(const io::CaseConfig& config);

/// Problems of the solver the fuzzer has found and that are not fixed yet: an accepted
/// input that would hit one skips the model stage (which would crash), so a run keeps
/// looking for new problems. Empty when none applies; otherwise what it is. README.md
/// lists them; remove a check here once its problem is fixed.
std::string known_problem(const io::CaseConfig& config);

/// One line describing a result, for reports and test failures.
std::string describe(const TargetResult& result);

}  // namespace hfdda::fuzz
