// Text checks of a case file around YAML parsing (case_text.hpp).

#include "io/case_text.hpp"

#include <string_view>
#include <vector>

#include "core/errors.hpp"
#include "io/case_schema.hpp"

namespace hfdda::io {

using namespace schema;

namespace {

std::string normalise_line_endings(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '\r') {
      out += text[i];
    } else {
      out += '\n';
      if (i + 1 < text.size() && text[i + 1] == '\n') ++i;
    }
  }
  return out;
}

bool is_blank(char c) { return c == ' ' || c == '\t'; }

/// A document marker line: `---` or `...` alone or followed by a blank.
bool is_marker(std::string_view line, std::string_view marker) {
  return line.starts_with(marker) && (line.size() == 3 || is_blank(line[3]));
}

/// Whether what is left of a line, from `pos`, is blank or a comment.
bool rest_is_empty(std::string_view line, std::size_t pos) {
  while (pos < line.size() && is_blank(line[pos])) ++pos;
  return pos == line.size() || line[pos] == '#';
}

/// A block scalar header (`key: |`, `- >-`): its value is the more indented lines below.
bool ends_with_block_scalar_header(std::string_view content) {
  while (!content.empty() && is_blank(content.back())) content.remove_suffix(1);
  std::size_t i = content.size();
  while (i > 0 && (content[i - 1] == '+' || content[i - 1] == '-' ||
                   (content[i - 1] >= '0' && content[i - 1] <= '9')))
    --i;
  if (i == 0 || (content[i - 1] != '|' && content[i - 1] != '>')) return false;
  --i;
  if (i == 0) return true;
  return is_blank(content[i - 1]) && i >= 2 &&
         (content[i - 2] == ':' || content[i - 2] == '-' || is_blank(content[i - 2]));
}

/// Walks the lines of a case file, tracking flow brackets, quotes and indentation.
class TextScanner {
 public:
  explicit TextScanner(std::string file) : file_(std::move(file)) {}

  void scan(const std::string& text) {
    std::size_t start = 0;
    int line_no = 0;
    while (start <= text.size()) {
      const std::size_t end = std::min(text.find('\n', start), text.size());
      ++line_no;
      scan_line(std::string_view(text).substr(start, end - start), line_no);
      if (end == text.size()) break;
      start = end + 1;
    }
  }

 private:
  [[noreturn]] void fail(int line, const std::string& key, const std::string& rule) const {
    throw InputError(file_, line, key, rule);
  }

  void scan_line(std::string_view line, int line_no) {
    std::size_t indent = 0;
    while (indent < line.size() && line[indent] == ' ') ++indent;
    if (const auto nul = line.find('\0'); nul != std::string_view::npos)
      fail(line_no, "(syntax)",
           "a NUL byte (0x00) at character " + std::to_string(nul + 1) +
               " of this line; a case file is text, and no key or value may hold one");
    if (block_scalar_indent_ >= 0) {  // text of a `|` or `>` value
      if (indent == line.size() || static_cast<int>(indent) > block_scalar_indent_) return;
      block_scalar_indent_ = -1;
    }
    // A directive (`%YAML 1.2`, `%TAG`) before the first `---` belongs to the one
    // document that follows it; YAML allows directives nowhere else.
    if (!content_seen_ && flow_depth_ == 0 && line.starts_with('%')) return;
    if (flow_depth_ == 0 && (is_marker(line, "---") || is_marker(line, "..."))) {
      if (is_marker(line, "---") && content_seen_)
        fail(line_no, "(document)",
             "a second YAML document starts here ('---'); a case file is one document");
      if (is_marker(line, "...")) document_end_ = line_no;
      if (rest_is_empty(line, 3)) return;
    }
    if (rest_is_empty(line, 0)) return;
    if (document_end_ > 0)
      fail(document_end_, "(document)",
           "'...' ends the YAML document here, but more follows on line " + std::to_string(line_no) +
               " and would be ignored; remove the '...'");
    content_seen_ = true;
    count_value(line_no);  // a line holds at least one value
    if (flow_depth_ == 0) {
      while (!indents_.empty() && indents_.back() > indent) indents_.pop_back();
      if (indents_.empty() || indents_.back() < indent) indents_.push_back(indent);
    }
    scan_tokens(line, indent, line_no, static_cast<int>(indents_.size()));
    if (flow_depth_ == 0 && ends_with_block_scalar_header(line.substr(0, content_end_)))
      block_scalar_indent_ = static_cast<int>(indent);
  }

  /// Quotes, comments and flow brackets of one line; `block_depth` is the nesting of its
  /// indentation (block maps and lists), to which `- ` items and open brackets add.
  void scan_tokens(std::string_view line, std::size_t from, int line_no, int block_depth) {
    char previous = 0;  // last non-blank character outside quotes (0: start of the line)
    content_end_ = line.size();
    for (std::size_t i = from; i < line.size(); ++i) {
      const char c = line[i];
      if (is_blank(c)) continue;
      // Where a scalar may start: a quote or bracket elsewhere belongs to a plain scalar
      // (`title: Griffith's crack`, `name: a-'b`).
      const bool token_start = previous == 0 || previous == ':' || previous == '[' ||
                               previous == '{' || previous == ',' ||
                               ((previous == '-' || previous == '?') && is_blank(line[i - 1]));
      if (c == '#' && (i == 0 || is_blank(line[i - 1]))) {
        content_end_ = i;
        return;
      }
      if ((c == '"' || c == '\'') && token_start) {
        i = closing_quote(line, i, line_no);
        previous = c;
        continue;
      }
      if ((c == '&' || c == '*') && token_start)  // a few aliases can expand to billions of nodes
        fail(line_no, "(syntax)",
             std::string("YAML anchors and aliases ('") + c + "') are not allowed: write each value out");
      if (c == '-' && previous == 0 && (i + 1 == line.size() || is_blank(line[i + 1]))) ++block_depth;
      if ((c == '[' || c == '{') && token_start) {
        ++flow_depth_;
        count_value(line_no);
      } else if ((c == ']' || c == '}') && flow_depth_ > 0) {
        --flow_depth_;
      } else if (c == ',' && flow_depth_ > 0) {
        count_value(line_no);
      }
      if (block_depth + flow_depth_ > kMaxNesting)
        fail(line_no, "(document)",
             "nesting too deep: more than " + std::to_string(kMaxNesting) +
                 " levels of maps and lists inside each other");
      if (c == '-' && previous == 0 && (i + 1 == line.size() || is_blank(line[i + 1]))) continue;
      previous = c;
    }
  }

  /// Counts one more value (a line, a flow collection or an item after a comma) and
  /// refuses the file before parsing once there are too many: yaml-cpp spends a few
  /// hundred bytes per node, so a 4 MiB list of a million items cost half a gigabyte.
  void count_value(int line_no) {
    if (++values_ <= kMaxCaseFileValues) return;
    fail(line_no, "(file)",
         "holds more than " + std::to_string(kMaxCaseFileValues) +
             " YAML values (lines, list items, maps) by this line; a case file may hold at most " +
             std::to_string(kMaxCaseFileValues) + " and one list at most " + std::to_string(kMaxListItems) +
             " items");
  }

  /// Index of the quote closing the one at `open`, on the same line.
  std::size_t closing_quote(std::string_view line, std::size_t open, int line_no) const {
    const char q = line[open];
    for (std::size_t i = open + 1; i < line.size(); ++i) {
      if (q == '"' && line[i] == '\\') {
        ++i;
      } else if (line[i] == q) {
        if (q == '\'' && i + 1 < line.size() && line[i + 1] == '\'') {
          ++i;
          continue;
        }
        return i;
      }
    }
    fail(line_no, "(syntax)",
         std::string("unclosed quote: the string opened with ") + q +
             " is not closed on this line (a quoted string must end on the line it starts on)");
  }

  std::string file_;
  int flow_depth_ = 0;
  std::vector<std::size_t> indents_;
  int block_scalar_indent_ = -1;
  bool content_seen_ = false;
  int document_end_ = 0;
  std::size_t content_end_ = 0;
  std::size_t values_ = 0;
};

class TreeChecker {
 public:
  explicit TreeChecker(std::string file) : file_(std::move(file)) {}

  void check(const YAML::Node& node, const std::string& key, int depth) {
    if (depth > kMaxNesting) fail(node, key, "nesting too deep: more than " + std::to_string(kMaxNesting) + " levels");
    const std::string& tag = node.Tag();
    if (!tag.empty() && tag != "?" && tag != "!")
      fail(node, key, "YAML tags such as '" + clip(tag_text(tag)) +
                          "' are not allowed: write the value alone (a number as 1.5, a string in quotes)");
    switch (node.Type()) {
      case YAML::NodeType::Scalar:
        if (!is_valid_utf8(node.Scalar()))
          fail(node, key, "is not valid UTF-8 text (byte " + first_bad_byte(node.Scalar()) +
                              "); save the case file as UTF-8");
        // A "\0" escape: a path would be cut there, a name would end early in the outputs.
        if (const auto nul = node.Scalar().find('\0'); nul != std::string::npos)
          fail(node, key, "holds a NUL byte (\\0) at character " + std::to_string(nul + 1) +
                              "; no value of a case file may hold one (a file path would be cut there)");
        break;
      case YAML::NodeType::Sequence:
        if (node.size() > kMaxListItems)
          fail(node, key, "a list of " + std::to_string(node.size()) + " items; at most " +
                              std::to_string(kMaxListItems) + " are allowed");
        for (std::size_t i = 0; i < node.size(); ++i) check(node[i], item_key(key, i), depth + 1);
        break;
      case YAML::NodeType::Map:
        for (const auto& entry : node) {
          const YAML::Node& name = entry.first;
          if (!name.IsScalar()) fail(name, key.empty() ? "(document)" : key, "a key must be a plain word");
          const std::string& text = name.Scalar();
          const std::string shown = clip(is_valid_utf8(text) ? text : std::string("(not UTF-8)"), 40);
          const std::string child = child_key(key, shown);
          if (!is_valid_utf8(text)) fail(name, child, "key is not valid UTF-8 text; save the case file as UTF-8");
          if (text.size() > kMaxKeyLength)
            fail(name, child, "key too long: " + std::to_string(text.size()) + " characters; at most " +
                                  std::to_string(kMaxKeyLength) + " are allowed");
          check(name, child, depth + 1);
          check(entry.second, child, depth + 1);
        }
        break;
      default: break;
    }
  }

 private:
  [[noreturn]] void fail(const YAML::Node& node, const std::string& key, const std::string& rule) const {
    throw InputError(file_, node.Mark().is_null() ? 0 : node.Mark().line + 1, key.empty() ? "(document)" : key,
                     rule);
  }

  static std::string tag_text(const std::string& tag) {
    const std::string_view core = "tag:yaml.org,2002:";
    return tag.starts_with(core) ? "!!" + tag.substr(core.size()) : tag;
  }

  static std::string first_bad_byte(const std::string& text) {
    static const char* hex = "0123456789ABCDEF";
    const std::size_t at = utf8_error_at(text);
    const auto b = static_cast<unsigned char>(text[at]);
    return std::string("0x") + hex[b >> 4] + hex[b & 15] + " at character " + std::to_string(at + 1);
  }

  std::string file_;
};

}  // namespace

std::size_t utf8_error_at(const std::string& text) {
  std::size_t i = 0;
  while (i < text.size()) {
    const auto b = static_cast<unsigned char>(text[i]);
    int extra = 0;
    unsigned cp = 0;
    if (b < 0x80) {
      ++i;
      continue;
    } else if ((b & 0xE0) == 0xC0) {
      extra = 1, cp = b & 0x1F;
    } else if ((b & 0xF0) == 0xE0) {
      extra = 2, cp = b & 0x0F;
    } else if ((b & 0xF8) == 0xF0) {
      extra = 3, cp = b & 0x07;
    } else {
      return i;
    }
    if (i + extra >= text.size()) return i;
    for (int k = 1; k <= extra; ++k) {
      const auto c = static_cast<unsigned char>(text[i + k]);
      if ((c & 0xC0) != 0x80) return i;
      cp = (cp << 6) | (c & 0x3F);
    }
    static const unsigned smallest[] = {0, 0x80, 0x800, 0x10000};
    if (cp < smallest[extra] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return i;
    i += extra + 1;
  }
  return std::string::npos;
}

bool is_valid_utf8(const std::string& text) { return utf8_error_at(text) == std::string::npos; }

std::string prepare_case_text(const std::string& text, const std::string& file) {
  if (text.size() > kMaxCaseFileBytes)
    throw InputError(file, 0, "(file)",
                     "is " + std::to_string(text.size()) + " bytes; a case file may be at most " +
                         std::to_string(kMaxCaseFileBytes) + " bytes (4 MiB)");
  std::string normalised = normalise_line_endings(text);
  TextScanner(file).scan(normalised);
  return normalised;
}

void check_yaml_tree(const YAML::Node& root, const std::string& file) {
  TreeChecker(file).check(root, "", 0);
}

}  // namespace hfdda::io
