// What the commands of the hfdda CLI share (cli_support.hpp).

#include "cli/cli_support.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>

namespace hfdda::cli {

namespace {

volatile std::sig_atomic_t stop_flag = 0;  // set by the signal handler only
const char* stop_notice = "";              // written by the handler: set before it is installed

extern "C" void on_stop_signal(int signal_number) {
  stop_flag = 1;
  std::signal(signal_number, SIG_DFL);
  // write(2) is async-signal-safe; a step can take minutes, so the user is told at once
  // that the signal was taken and how to stop without waiting.
  const ssize_t written = write(STDERR_FILENO, stop_notice, std::strlen(stop_notice));
  (void)written;
}

}  // namespace

void catch_stop_signals(const char* notice) {
  stop_notice = notice;
  std::signal(SIGINT, on_stop_signal);
  std::signal(SIGTERM, on_stop_signal);
}

bool stop_requested() { return stop_flag != 0; }

int run_python_script(const char* command, const std::string& script_name, const std::vector<std::string>& arguments) {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  const std::filesystem::path script = exe.parent_path() / script_name;
  if (ec || !std::filesystem::exists(script)) {
    std::fprintf(stderr, "hfdda: %s: %s not found (it is copied next to the hfdda binary by the build)\n", command,
                 script.c_str());
    return 2;
  }
  const char* python = "/usr/bin/python3";
  if (access(python, X_OK) != 0) {
    std::fprintf(stderr, "hfdda: %s: %s not found; install Debian's python3 and python3-matplotlib\n", command,
                 python);
    return 2;
  }
  std::vector<std::string> args{python, script.string()};
  args.insert(args.end(), arguments.begin(), arguments.end());
  std::vector<char*> c_args;
  for (std::string& a : args) c_args.push_back(a.data());
  c_args.push_back(nullptr);
  std::fflush(stdout);
  std::fflush(stderr);
  const pid_t pid = fork();
  if (pid < 0) return 2;
  if (pid == 0) {
    execv(python, c_args.data());
    _exit(127);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 2;
}

}  // namespace hfdda::cli
