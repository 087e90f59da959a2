#pragma once
// Error types. Input errors are always checked and name the file, line, key and the
// rule broken; internal invariants use assert() (checked in debug builds only).

#include <stdexcept>
#include <string>

namespace hfdda {

/// Bad input: thrown before anything is written. what() reads
/// "FILE:LINE: key 'KEY': RULE" (line 0 when no line applies).
class InputError : public std::runtime_error {
 public:
  InputError(std::string file, int line, std::string key, std::string rule)
      : std::runtime_error(file + ":" + std::to_string(line) + ": key '" + key + "': " + rule),
        file_(std::move(file)), line_(line), key_(std::move(key)), rule_(std::move(rule)) {}
  const std::string& file() const { return file_; }
  int line() const { return line_; }
  const std::string& key() const { return key_; }
  const std::string& rule() const { return rule_; }

 private:
  std::string file_;
  int line_;
  std::string key_;
  std::string rule_;
};

/// A mesh or model that cannot be built (degenerate block, fracture off the mesh, ...).
class ModelError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A time step that could not be converged; the caller keeps what was computed.
class ConvergenceError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A step abandoned on request (a stop signal) before it ended; the step's attempt was
/// rolled back, so the state is that of the step's start.
class StepInterrupted : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace hfdda
