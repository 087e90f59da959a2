#pragma once
// Helpers shared by the case-file tests (test_case_*.cpp): where the test cases are,
// and checks on the file, line, key and rule of an InputError.

#include <gtest/gtest.h>

#include <optional>
#include <string>

#include "core/errors.hpp"
#include "io/case_config.hpp"

namespace hfdda::io::case_test {

inline const std::string kCases = std::string(HFDDA_TEST_DATA_DIR) + "/cases/";

inline std::optional<InputError> error_of_text(const std::string& yaml,
                                               const std::string& label = "case.yaml") {
  try {
    load_case_text(yaml, label);
  } catch (const InputError& e) {
    return e;
  }
  return std::nullopt;
}

inline std::optional<InputError> error_of_file(const std::string& path) {
  try {
    load_case_file(path);
  } catch (const InputError& e) {
    return e;
  }
  return std::nullopt;
}

/// Checks file, line and key exactly, and that the rule contains `rule_part`.
inline void expect_error(const std::optional<InputError>& error, const std::string& file,
                         int line, const std::string& key, const std::string& rule_part = "") {
  ASSERT_TRUE(error.has_value()) << "no InputError thrown";
  EXPECT_EQ(error->file(), file) << error->what();
  EXPECT_EQ(error->line(), line) << error->what();
  EXPECT_EQ(error->key(), key) << error->what();
  EXPECT_NE(error->rule().find(rule_part), std::string::npos) << error->what();
}

inline void expect_text_error(const std::string& yaml, int line, const std::string& key,
                              const std::string& rule_part = "") {
  SCOPED_TRACE(yaml);
  expect_error(error_of_text(yaml), "case.yaml", line, key, rule_part);
}

}  // namespace hfdda::io::case_test
