#pragma once
// Keeps the input a fuzz run is on where a crash, a sanitizer report or a hang can still
// save it: a signal handler, the sanitizers' death callback and a watchdog thread write
// it to a file and say where, so every finding can be run again.

#include <atomic>
#include <cstdint>
#include <string>
#include <string_view>
#include <thread>

namespace hfdda::fuzz {

class CrashGuard {
 public:
  /// Installs the handlers; an input running longer than `timeout_s` ends the process
  /// (exit code 3) after it is saved.
  explicit CrashGuard(double timeout_s);
  ~CrashGuard();
  CrashGuard(const CrashGuard&) = delete;
  CrashGuard& operator=(const CrashGuard&) = delete;

  /// The input about to run, the file it is saved to on a crash (empty: the input is
  /// that file, `name`), and how to name it.
  void enter(std::string_view input, const std::string& save_path, const std::string& name);
  /// The input returned.
  void leave();

 private:
  void watch(double timeout_s);

  std::atomic<bool> stop_{false};
  std::thread watchdog_;
};

}  // namespace hfdda::fuzz
