#include "core/environment.hpp"

#include <cstdlib>
#include <stdexcept>

namespace hfdda::core {

int whole_number_from_environment(const char* name, int fallback, int max) {
  const char* text = std::getenv(name);
  if (text == nullptr || *text == '\0') return fallback;
  char* end = nullptr;
  const long value = std::strtol(text, &end, 10);
  if (*end != '\0' || value < 1 || value > max)
    throw std::invalid_argument(std::string(name) + " must be a whole number from 1 to " + std::to_string(max) +
                                " (got '" + text + "')");
  return static_cast<int>(value);
}

}  // namespace hfdda::core
