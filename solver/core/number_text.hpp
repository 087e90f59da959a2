#pragma once
// Numbers in messages and generated docs: the shortest text that reads back to the same
// double, with YAML-style exponents ("5e6", "1e-4", not "5e+06").

#include <string>

namespace hfdda {

std::string number_text(double value);

}  // namespace hfdda
