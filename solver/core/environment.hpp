#pragma once
// Settings read from the environment (HFDDA_THREADS, HFDDA_VERIFY_JOBS).

#include <string>

namespace hfdda::core {

/// The value of environment variable `name` as a whole number from 1 to `max`, or
/// `fallback` when it is unset or empty. Throws std::invalid_argument naming the variable
/// and the rule for any other value.
int whole_number_from_environment(const char* name, int fallback, int max);

}  // namespace hfdda::core
