#pragma once
// What the commands of the hfdda CLI share: the stop signals and the figure scripts.

#include <string>
#include <vector>

namespace hfdda::cli {

/// First SIGINT/SIGTERM: stop_requested() turns true (the command finishes its step and
/// stops cleanly) and `notice` (a string literal: what happens now, and that a second
/// signal stops at once) is written to stderr; a second one ends the process at once
/// (the default action).
void catch_stop_signals(const char* notice);
bool stop_requested();

/// Runs `script_name` (found next to this executable) with Debian's Python, the one that
/// sees python3-matplotlib, and `arguments`; its exit code (2 when it cannot be run).
/// `command` names the caller in messages.
int run_python_script(const char* command, const std::string& script_name, const std::vector<std::string>& arguments);

}  // namespace hfdda::cli
