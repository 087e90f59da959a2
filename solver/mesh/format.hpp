#pragma once
// Number formatting for mesh error messages (internal to the mesh builders).

#include <sstream>
#include <string>

namespace hfdda::mesh::detail {

/// A value with 12 significant digits, as quoted in ModelError messages.
inline std::string num(double v) {
  std::ostringstream s;
  s.precision(12);
  s << v;
  return s.str();
}

}  // namespace hfdda::mesh::detail
