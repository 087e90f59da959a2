#pragma once
// Checks on the text of a case file made before and right after YAML parsing, for YAML
// that is valid but would mean something other than what was written (a quote left
// open swallowing the rest of the file, a second document, `...` in the middle, tags,
// NUL bytes), and for input too large or too deeply nested to parse safely. Directives
// (`%YAML 1.2`) before the first `---` belong to the one document.

#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <string>

namespace hfdda::io {

/// Limits on the text of one case file.
inline constexpr std::size_t kMaxCaseFileBytes = 4u << 20;  ///< 4 MiB
inline constexpr int kMaxNesting = 16;                       ///< maps and lists inside each other
inline constexpr std::size_t kMaxKeyLength = 64;             ///< characters of one key
inline constexpr std::size_t kMaxListItems = 100000;         ///< items of any one YAML list
inline constexpr std::size_t kMaxCaseFileValues = 400000;    ///< values of the whole file, counted before parsing

/// The text with CR LF and lone CR line endings turned into LF, after checking its size,
/// nesting, quotes and document markers. Throws InputError naming `file` and the line.
std::string prepare_case_text(const std::string& text, const std::string& file);

/// Checks every node of the parsed document: no explicit tags, valid UTF-8 in every
/// string, keys of at most kMaxKeyLength characters, lists of at most kMaxListItems items.
void check_yaml_tree(const YAML::Node& root, const std::string& file);

/// Index of the first byte of `text` that is not part of a valid UTF-8 sequence
/// (std::string::npos when there is none).
std::size_t utf8_error_at(const std::string& text);

/// Whether `text` is valid UTF-8 (no stray, truncated, overlong or surrogate sequences).
bool is_valid_utf8(const std::string& text);

}  // namespace hfdda::io
