// Text helpers, scalar readers and ranges of the case-file key tables (case_schema.hpp).

#include "io/case_schema.hpp"

#include "core/number_text.hpp"

#include <algorithm>
#include <charconv>
#include <cctype>
#include <cmath>
#include <optional>
#include <utility>

namespace hfdda::io::schema {

// ---------------------------------------------------------------------------
// Text helpers

std::string format_number(double v) { return number_text(v); }

std::string format_point(const Vec2& p) {
  // Appended piece by piece: `"[" + std::string` trips a false -Wrestrict in GCC 12.
  std::string text = "[";
  text += format_number(p.x()) + ", " + format_number(p.y()) + "]";
  return text;
}

std::string format_rect(const Rect& r) {
  std::string text = "{xmin: ";
  text += format_number(r.xmin) + ", xmax: " + format_number(r.xmax) +
          ", ymin: " + format_number(r.ymin) + ", ymax: " + format_number(r.ymax) + "}";
  return text;
}

std::string join(const std::vector<std::string>& items, const std::string& separator) {
  std::string text;
  for (const auto& item : items) text += (text.empty() ? "" : separator) + item;
  return text;
}

std::string child_key(const std::string& prefix, const std::string& name) {
  return prefix.empty() ? name : prefix + "." + name;
}

std::string item_key(const std::string& prefix, std::size_t index) {
  return prefix + "[" + std::to_string(index) + "]";
}

std::string clip(std::string_view text, std::size_t max) {
  if (text.size() <= max) return std::string(text);
  std::size_t cut = max > 3 ? max - 3 : 0;
  while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;  // whole UTF-8 characters
  return std::string(text.substr(0, cut)) + "...";
}

std::string describe(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Scalar:
      return (node.Tag() == "!" ? "the quoted string '" : "'") + clip(node.Scalar()) + "'";
    case YAML::NodeType::Sequence: return "a list";
    case YAML::NodeType::Map: return "a map";
    case YAML::NodeType::Null: return "null";
    default: return "nothing";
  }
}

// ---------------------------------------------------------------------------
// Scalar readers

namespace {

std::optional<double> parse_double(std::string_view text) {
  if (text.starts_with('+')) text.remove_prefix(1);
  double value = 0.0;
  const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
  if (result.ec != std::errc() || result.ptr != text.data() + text.size()) return std::nullopt;
  return value;
}

std::optional<int> parse_int(std::string_view text) {
  if (text.starts_with('+')) text.remove_prefix(1);
  int value = 0;
  const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
  if (result.ec != std::errc() || result.ptr != text.data() + text.size()) return std::nullopt;
  return value;
}

/// A plain (unquoted) scalar: YAML types a quoted "5" as a string, and so do we.
bool is_plain_scalar(const YAML::Node& node) { return node.IsScalar() && node.Tag() != "!"; }

/// "1,5": a number written with a decimal comma; returns "1.5".
std::optional<std::string> decimal_comma(const std::string& text) {
  const auto comma = text.find(',');
  if (comma == std::string::npos || text.find(',', comma + 1) != std::string::npos) return std::nullopt;
  std::string dotted = text;
  dotted[comma] = '.';
  if (!parse_double(dotted) || comma == 0 || !std::isdigit(static_cast<unsigned char>(text[comma - 1])) ||
      comma + 1 == text.size() || !std::isdigit(static_cast<unsigned char>(text[comma + 1])))
    return std::nullopt;
  return dotted;
}

void fail_decimal_comma(const FileReader& r, const YAML::Node& node, const std::string& key) {
  if (!is_plain_scalar(node)) return;
  if (const auto dotted = decimal_comma(node.Scalar()))
    r.fail(node, key, "decimal comma? write " + clip(*dotted) + " (got '" + clip(node.Scalar()) + "')");
}

bool is_whole_number(std::string_view text) {
  if (text.starts_with('+') || text.starts_with('-')) text.remove_prefix(1);
  return !text.empty() && std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
}

/// `b` is written right after `a` and a comma, with no blank between: "1,5" in a flow
/// collection, which YAML reads as two values.
bool follows_comma_directly(const YAML::Node& a, const YAML::Node& b) {
  if (!is_plain_scalar(a) || a.Mark().is_null() || b.Mark().is_null()) return false;
  return b.Mark().line == a.Mark().line &&
         b.Mark().column == a.Mark().column + static_cast<int>(a.Scalar().size()) + 1;
}

}  // namespace

void fail_split_decimal_comma(const FileReader& r, const YAML::Node& map, const YAML::Node& name_node,
                              const std::string& prefix) {
  const std::string& digits = name_node.Scalar();
  if (!is_plain_scalar(name_node) || !is_whole_number(digits) || digits.starts_with('-') || digits.starts_with('+'))
    return;
  // Copies, not assignments: assigning a YAML::Node changes the node it refers to.
  std::optional<std::pair<YAML::Node, YAML::Node>> previous;
  for (const auto& entry : map) {
    if (entry.first.is(name_node)) {
      if (!entry.second.IsNull()) return;  // `5: 3` is an unknown key, not a split number
      break;
    }
    previous.emplace(entry.first, entry.second);
  }
  if (!previous) return;
  const auto& [previous_name, previous_value] = *previous;
  if (!previous_name.IsScalar() || !is_plain_scalar(previous_value) || !is_whole_number(previous_value.Scalar()) ||
      !follows_comma_directly(previous_value, name_node))
    return;
  const std::string written = previous_value.Scalar() + "," + name_node.Scalar();
  r.fail(previous_value, child_key(prefix, previous_name.Scalar()),
         "decimal comma? write " + clip(previous_value.Scalar() + "." + name_node.Scalar()) + " (got '" +
             clip(written) + "', which a { } map reads as the value " + clip(previous_value.Scalar()) +
             " and a key '" + clip(name_node.Scalar()) + "')");
}

double read_number(const FileReader& r, const YAML::Node& node, const std::string& key) {
  const auto value = is_plain_scalar(node) ? parse_double(node.Scalar()) : std::nullopt;
  if (!value) fail_decimal_comma(r, node, key);
  if (!value || !std::isfinite(*value))
    r.fail(node, key, "expected a finite number (got " + describe(node) + ")");
  return *value;
}

int read_integer(const FileReader& r, const YAML::Node& node, const std::string& key) {
  const auto value = is_plain_scalar(node) ? parse_int(node.Scalar()) : std::nullopt;
  if (!value) fail_decimal_comma(r, node, key);
  if (!value && is_plain_scalar(node)) {
    std::string_view digits = node.Scalar();
    if (digits.starts_with('+') || digits.starts_with('-')) digits.remove_prefix(1);
    if (!digits.empty() && std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
      r.fail(node, key, "is far too large (got '" + clip(node.Scalar()) + "'; see the allowed range of the key)");
  }
  if (!value) r.fail(node, key, "expected an integer (got " + describe(node) + ")");
  return *value;
}

bool read_bool(const FileReader& r, const YAML::Node& node, const std::string& key) {
  if (is_plain_scalar(node)) {
    const std::string& s = node.Scalar();
    if (s == "true" || s == "True" || s == "TRUE") return true;
    if (s == "false" || s == "False" || s == "FALSE") return false;
  }
  r.fail(node, key, "expected a boolean, true or false (got " + describe(node) + ")");
}

std::string read_string(const FileReader& r, const YAML::Node& node, const std::string& key) {
  if (!node.IsScalar()) r.fail(node, key, "expected a string (got " + describe(node) + ")");
  return node.Scalar();
}

Vec2 read_point(const FileReader& r, const YAML::Node& node, const std::string& key) {
  if (!node.IsSequence() || node.size() != 2) {
    std::string got = node.IsSequence() ? "a list of " + std::to_string(node.size()) + " items" : describe(node);
    for (std::size_t i = 0; node.IsSequence() && i + 1 < node.size(); ++i)
      if (is_whole_number(node[i].Scalar()) && is_plain_scalar(node[i + 1]) &&
          is_whole_number(node[i + 1].Scalar()) && follows_comma_directly(node[i], node[i + 1])) {
        got += "; decimal comma? '" + clip(node[i].Scalar() + "," + node[i + 1].Scalar()) +
               "' is two items in [ ]: write " + clip(node[i].Scalar() + "." + node[i + 1].Scalar());
        break;
      }
    r.fail(node, key, "expected a point [x, y], a list of 2 numbers (got " + got + ")");
  }
  return Vec2{read_number(r, node[0], key), read_number(r, node[1], key)};
}

// ---------------------------------------------------------------------------
// Ranges and key documentation

std::string Range::text() const {
  if (lo && hi)
    return std::string(lo_open ? "(" : "[") + format_number(*lo) + ", " + format_number(*hi) +
           (hi_open ? ")" : "]");
  if (lo) return std::string(lo_open ? "> " : ">= ") + format_number(*lo);
  if (hi) return std::string(hi_open ? "< " : "<= ") + format_number(*hi);
  return "any";
}

void check_range(const FileReader& r, const YAML::Node& node, const std::string& key,
                 const Range& range, double value) {
  if (!range.contains(value))
    r.fail(node, key, "must be " + range.rule() + " (got " + format_number(value) + ")");
}

KeyDoc key_doc(const Doc& d, std::string type, std::string default_text, std::string allowed) {
  KeyDoc doc;
  doc.name = d.name;
  doc.type = std::move(type);
  doc.unit = d.unit;
  doc.default_text = std::move(default_text);
  doc.allowed = std::move(allowed);
  doc.seed = d.seed;
  doc.description = d.description;
  return doc;
}

}  // namespace hfdda::io::schema
