// libFuzzer entry point: the same target as hfdda_fuzz_cases, guided by coverage.
// Built only with clang and HFDDA_LIBFUZZER=ON (README.md). A finding aborts, so
// libFuzzer saves the input as crash-<sha1>.

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "case_reader_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const hfdda::fuzz::TargetResult result = hfdda::fuzz::run_case_reader(input);
  if (result.outcome == hfdda::fuzz::Outcome::finding) {
    std::fprintf(stderr, "hfdda libFuzzer: %s\n", hfdda::fuzz::describe(result).c_str());
    std::abort();
  }
  return 0;
}
