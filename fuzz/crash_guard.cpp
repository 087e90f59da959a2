// Saving the running input on a crash, a sanitizer report or a hang (crash_guard.hpp).

#include "crash_guard.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>

#if defined(__SANITIZE_ADDRESS__)
#define HFDDA_FUZZ_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(undefined_behavior_sanitizer)
#define HFDDA_FUZZ_SANITIZED 1
#endif
#endif
#ifdef HFDDA_FUZZ_SANITIZED
#include <sanitizer/common_interface_defs.h>
#endif

namespace hfdda::fuzz {

namespace {

/// The running input. Signal handlers and the sanitizers' death callback take no
/// argument, so this one object has to be static; it is written only by the fuzzing
/// thread, between inputs.
struct Running {
  std::atomic<const char*> data{nullptr};
  std::atomic<std::size_t> size{0};
  std::atomic<std::int64_t> started_ms{0};  ///< 0: no input running
  char path[2048] = {};
  char name[512] = {};
};
Running running;

std::int64_t now_ms() {
  return std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

// Only async-signal-safe calls from here on: open, write, close.
void write_text(const char* text) {
  std::size_t left = std::strlen(text);
  while (left > 0) {
    const ssize_t n = ::write(STDERR_FILENO, text, left);
    if (n <= 0) return;
    text += n;
    left -= static_cast<std::size_t>(n);
  }
}

/// Saves the running input to its path (none: it is a file already) and says how to
/// run it again.
void save_running_input(const char* why) {
  const char* data = running.data.load();
  if (data == nullptr) return;
  std::size_t left = running.size.load();
  const bool save = running.path[0] != '\0';
  const int fd = save ? ::open(running.path, O_WRONLY | O_CREAT | O_TRUNC, 0644) : -1;
  if (fd >= 0) {
    while (left > 0) {
      const ssize_t n = ::write(fd, data, left);
      if (n <= 0) break;
      data += n;
      left -= static_cast<std::size_t>(n);
    }
    ::close(fd);
  }
  write_text("\nhfdda_fuzz_cases: FINDING: ");
  write_text(why);
  write_text(" on ");
  write_text(running.name);
  if (save) {
    write_text("\nhfdda_fuzz_cases: input saved to ");
    write_text(running.path);
  }
  write_text("\nhfdda_fuzz_cases: reproduce with: hfdda_fuzz_cases ");
  write_text(save ? running.path : running.name);
  write_text("\n");
}

void on_fatal_signal(int signal) {
  save_running_input(signal == SIGABRT ? "abort (SIGABRT)" : "crash (fatal signal)");
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}

#ifdef HFDDA_FUZZ_SANITIZED
void on_sanitizer_report() { save_running_input("sanitizer report (see above)"); }
// The sanitizers catch SIGSEGV, SIGBUS and SIGFPE themselves and then call the callback.
constexpr int kSignals[] = {SIGABRT, SIGILL};
#else
constexpr int kSignals[] = {SIGABRT, SIGILL, SIGSEGV, SIGBUS, SIGFPE};
#endif

void copy_clipped(char* to, std::size_t capacity, const std::string& from) {
  const std::size_t n = std::min(from.size(), capacity - 1);
  std::memcpy(to, from.data(), n);
  to[n] = '\0';
}

}  // namespace

CrashGuard::CrashGuard(double timeout_s) {
  for (const int s : kSignals) std::signal(s, on_fatal_signal);
#ifdef HFDDA_FUZZ_SANITIZED
  __sanitizer_set_death_callback(on_sanitizer_report);
#endif
  watchdog_ = std::thread([this, timeout_s] { watch(timeout_s); });
}

CrashGuard::~CrashGuard() {
  stop_ = true;
  watchdog_.join();
  for (const int s : kSignals) std::signal(s, SIG_DFL);
#ifdef HFDDA_FUZZ_SANITIZED
  __sanitizer_set_death_callback(nullptr);
#endif
}

void CrashGuard::enter(std::string_view input, const std::string& save_path, const std::string& name) {
  copy_clipped(running.path, sizeof running.path, save_path);
  copy_clipped(running.name, sizeof running.name, name);
  running.size = input.size();
  running.data = input.data();
  running.started_ms = now_ms();
}

void CrashGuard::leave() {
  running.started_ms = 0;
  running.data = nullptr;
}

void CrashGuard::watch(double timeout_s) {
  const auto limit_ms = static_cast<std::int64_t>(timeout_s * 1000.0);
  while (!stop_) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    const std::int64_t started = running.started_ms.load();
    if (started == 0 || now_ms() - started <= limit_ms) continue;
    // Still the same input (no leave() since): the fuzzing thread is stuck in it.
    if (running.started_ms.load() != started) continue;
    char why[100];
    std::snprintf(why, sizeof why, "hang (an input ran longer than %g s)", timeout_s);
    save_running_input(why);
    ::_exit(3);
  }
}

}  // namespace hfdda::fuzz

// UndefinedBehaviorSanitizer has its own copy of the sanitizers' common runtime, which
// does not call the death callback set above: let it end with abort(), whose SIGABRT
// the handler above catches. Read by the UBSan runtime, if linked; unused otherwise.
extern "C" const char* __ubsan_default_options() { return "abort_on_error=1:print_stacktrace=1"; }
