// YAML case-file loader (declared in case_config.hpp).
//
// Every key is declared once, in the key tables below (name, type, unit, default,
// allowed range, seed source, description). The same tables drive parsing, the range
// checks and the reference in docs/case_file.md (case_file_reference_markdown), so the
// documentation cannot drift from the code (STYLE.md item 7). Defaults are not
// repeated here: they are read from the default-constructed config structs.
//
// Errors are InputError(file, line, dotted key, rule) (STYLE.md item 10). Checks that
// involve two sections (a fracture inside the domain, end_time >= dt, ...) run after
// the whole extends chain is merged, using the recorded file and line of every key.

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/errors.hpp"
#include "io/case_config.hpp"

namespace hfdda::io {
namespace {

// ---------------------------------------------------------------------------
// Text helpers

/// Shortest text that reads back to v, with YAML-style exponents ("2.5e10", "1e-7").
std::string format_number(double v) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
  std::string text(buffer, result.ptr);
  const auto e = text.find('e');
  if (e == std::string::npos) return text;
  std::string exponent = text.substr(e + 1);
  const bool negative = exponent.front() == '-';
  if (exponent.front() == '+' || exponent.front() == '-') exponent.erase(0, 1);
  exponent.erase(0, std::min(exponent.find_first_not_of('0'), exponent.size() - 1));
  return text.substr(0, e) + "e" + (negative ? "-" : "") + exponent;
}

std::string format_point(const Vec2& p) {
  return "[" + format_number(p.x()) + ", " + format_number(p.y()) + "]";
}

std::string format_rect(const Rect& r) {
  return "{xmin: " + format_number(r.xmin) + ", xmax: " + format_number(r.xmax) +
         ", ymin: " + format_number(r.ymin) + ", ymax: " + format_number(r.ymax) + "}";
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

/// How a node reads in an error message: "'abc'", "a list", "a map", "null"; quoted
/// scalars say so, because YAML types them as strings.
std::string describe(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Scalar:
      return (node.Tag() == "!" ? "the quoted string '" : "'") + node.Scalar() + "'";
    case YAML::NodeType::Sequence: return "a list";
    case YAML::NodeType::Map: return "a map";
    case YAML::NodeType::Null: return "null";
    default: return "nothing";
  }
}

// ---------------------------------------------------------------------------
// Where keys come from

struct Location {
  std::string file;
  int line = 0;
};

/// File and line where each key present in the case files was last set, keyed by
/// dotted path ("materials[1].box"). Checks made after merging the extends chain use it
/// to name the file the offending key is in.
using Provenance = std::map<std::string, Location>;

/// Parse state of one file of the extends chain.
class FileReader {
 public:
  FileReader(std::string file, Provenance& where) : file_(std::move(file)), where_(&where) {}

  const std::string& file() const { return file_; }

  /// 1-based line of a node. yaml-cpp marks an empty value (`key:`) at the next token,
  /// so null nodes take the line of the key that holds them (set_null_line).
  int line(const YAML::Node& node) const {
    if (node.IsNull() || node.Mark().is_null()) return null_line_;
    return node.Mark().line + 1;
  }
  void set_null_line(int line) { null_line_ = line; }

  [[noreturn]] void fail(const YAML::Node& node, const std::string& key,
                         const std::string& rule) const {
    throw InputError(file_, line(node), key, rule);
  }

  void record(const std::string& key, const YAML::Node& node) {
    (*where_)[key] = Location{file_, line(node)};
  }

  /// Drops what was recorded under `prefix` (a list replaced as a whole).
  void forget(const std::string& prefix) {
    auto it = where_->lower_bound(prefix);
    while (it != where_->end() && it->first.starts_with(prefix)) it = where_->erase(it);
  }

 private:
  std::string file_;
  Provenance* where_;  // not owned: shared by every file of the chain
  int null_line_ = 0;
};

// ---------------------------------------------------------------------------
// Scalar readers (type checks)

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

double read_number(const FileReader& r, const YAML::Node& node, const std::string& key) {
  const auto value = is_plain_scalar(node) ? parse_double(node.Scalar()) : std::nullopt;
  if (!value || !std::isfinite(*value))
    r.fail(node, key, "expected a finite number (got " + describe(node) + ")");
  return *value;
}

int read_integer(const FileReader& r, const YAML::Node& node, const std::string& key) {
  const auto value = is_plain_scalar(node) ? parse_int(node.Scalar()) : std::nullopt;
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
    const std::string got = node.IsSequence()
                                ? "a list of " + std::to_string(node.size()) + " items"
                                : describe(node);
    r.fail(node, key, "expected a point [x, y], a list of 2 numbers (got " + got + ")");
  }
  return Vec2{read_number(r, node[0], key), read_number(r, node[1], key)};
}

// ---------------------------------------------------------------------------
// Ranges

/// Allowed interval of a number; unset bounds are open-ended.
struct Range {
  std::optional<double> lo, hi;
  bool lo_open = false, hi_open = false;

  bool contains(double v) const {
    if (lo && (lo_open ? v <= *lo : v < *lo)) return false;
    if (hi && (hi_open ? v >= *hi : v > *hi)) return false;
    return true;
  }
  std::string text() const {
    if (lo && hi)
      return std::string(lo_open ? "(" : "[") + format_number(*lo) + ", " + format_number(*hi) +
             (hi_open ? ")" : "]");
    if (lo) return std::string(lo_open ? "> " : ">= ") + format_number(*lo);
    if (hi) return std::string(hi_open ? "< " : "<= ") + format_number(*hi);
    return "any";
  }
  /// Completes "must be ...".
  std::string rule() const { return lo && hi ? "in " + text() : text(); }
};

Range any_value() { return {}; }
Range greater_than(double lo) { return {lo, std::nullopt, true, false}; }
Range at_least(double lo) { return {lo, std::nullopt, false, false}; }
Range interval(double lo, bool lo_open, double hi, bool hi_open) {
  return {lo, hi, lo_open, hi_open};
}

void check_range(const FileReader& r, const YAML::Node& node, const std::string& key,
                 const Range& range, double value) {
  if (!range.contains(value))
    r.fail(node, key, "must be " + range.rule() + " (got " + format_number(value) + ")");
}

// ---------------------------------------------------------------------------
// Key tables

struct SectionDoc;

/// One row of the reference: what a key is, as written in docs/case_file.md.
struct KeyDoc {
  std::string name, type, unit, default_text, allowed, seed, description;
  bool required = false;
  std::function<SectionDoc()> child;  ///< the table of a nested map, if any
};

struct SectionDoc {
  std::string title;
  std::string note;
  std::vector<KeyDoc> rows;
};

/// The descriptive part of a key, written in the tables below.
struct Doc {
  std::string name, unit, seed, description;
};

template <class T>
using ReadFn = std::function<void(FileReader&, const YAML::Node&, const std::string& key, T&)>;

/// A key of section T: its documentation and how to read it into a T.
template <class T>
struct Field {
  KeyDoc doc;
  ReadFn<T> read;
};

/// A section: the keys of one config struct, and the heading and note of its docs table.
template <class T>
struct Table {
  std::string title;
  std::string note;
  std::vector<Field<T>> fields;
};

template <class T>
SectionDoc section_doc(const Table<T>& table) {
  SectionDoc doc{table.title, table.note, {}};
  for (const auto& field : table.fields) doc.rows.push_back(field.doc);
  return doc;
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

/// Parses map `node` into `out`: only the keys present override (extends merging).
/// Returns the names present, for checks on a complete item.
template <class T>
std::set<std::string> parse_map(FileReader& r, const YAML::Node& node, const std::string& prefix,
                                const Table<T>& table, T& out) {
  if (!node.IsMap())
    r.fail(node, prefix.empty() ? "(document)" : prefix,
           "expected a map of keys (got " + describe(node) + ")");
  std::set<std::string> seen;
  for (const auto& entry : node) {
    const YAML::Node& name_node = entry.first;
    const std::string name = name_node.IsScalar() ? name_node.Scalar() : std::string();
    const std::string key = child_key(prefix, name);
    const Field<T>* field = nullptr;
    for (const auto& f : table.fields)
      if (f.doc.name == name) field = &f;
    if (field == nullptr) {
      std::vector<std::string> names;
      for (const auto& f : table.fields) names.push_back(f.doc.name);
      r.fail(name_node, key, "unknown key; allowed keys: " + join(names, ", "));
    }
    if (!seen.insert(name).second) r.fail(name_node, key, "duplicate key");
    r.set_null_line(r.line(name_node));
    r.record(key, name_node);  // the key's line: a block map or list starts below it
    field->read(r, entry.second, key, out);
  }
  for (const auto& f : table.fields)
    if (f.doc.required && !seen.contains(f.doc.name))
      r.fail(node, child_key(prefix, f.doc.name), "is required");
  return seen;
}

// --- Field kinds ------------------------------------------------------------

/// A number in `range`; `also` documents a check made on the merged case.
template <class T>
Field<T> number(Doc d, double T::*member, Range range, std::string also = "") {
  auto read = [member, range](FileReader& r, const YAML::Node& n, const std::string& key, T& out) {
    const double value = read_number(r, n, key);
    check_range(r, n, key, range, value);
    out.*member = value;
  };
  const std::string allowed = also.empty() ? range.text() : range.text() + ", " + also;
  return {key_doc(d, "number", format_number(T{}.*member), allowed), read};
}

/// A number that, when absent, is taken from elsewhere (`fallback` names where).
template <class T>
Field<T> optional_number(Doc d, std::optional<double> T::*member, Range range,
                         std::string fallback) {
  auto read = [member, range](FileReader& r, const YAML::Node& n, const std::string& key, T& out) {
    if (n.IsNull()) {
      (out.*member).reset();
      return;
    }
    const double value = read_number(r, n, key);
    check_range(r, n, key, range, value);
    out.*member = value;
  };
  return {key_doc(d, "number", std::move(fallback), range.text()), read};
}

template <class T>
Field<T> integer(Doc d, int T::*member, Range range) {
  auto read = [member, range](FileReader& r, const YAML::Node& n, const std::string& key, T& out) {
    const int value = read_integer(r, n, key);
    check_range(r, n, key, range, value);
    out.*member = value;
  };
  return {key_doc(d, "integer", std::to_string(T{}.*member), range.text()), read};
}

template <class T>
Field<T> boolean(Doc d, bool T::*member) {
  auto read = [member](FileReader& r, const YAML::Node& n, const std::string& key, T& out) {
    out.*member = read_bool(r, n, key);
  };
  return {key_doc(d, "boolean", T{}.*member ? "true" : "false", "true, false"), read};
}

template <class T>
Field<T> optional_boolean(Doc d, std::optional<bool> T::*member, std::string fallback) {
  auto read = [member](FileReader& r, const YAML::Node& n, const std::string& key, T& out) {
    if (n.IsNull())
      (out.*member).reset();
    else
      out.*member = read_bool(r, n, key);
  };
  return {key_doc(d, "boolean", std::move(fallback), "true, false"), read};
}

template <class T>
Field<T> text(Doc d, std::string T::*member) {
  auto read = [member](FileReader& r, const YAML::Node& n, const std::string& key, T& out) {
    out.*member = read_string(r, n, key);
  };
  const std::string value = T{}.*member;
  return {key_doc(d, "string", value.empty() ? "(empty)" : "\"" + value + "\"", "any"), read};
}

template <class M>
using Choices = std::vector<std::pair<std::string, M>>;

template <class M>
std::vector<std::string> choice_names(const Choices<M>& choices) {
  std::vector<std::string> names;
  for (const auto& [name, value] : choices) names.push_back(name);
  return names;
}

template <class M>
M read_choice(const FileReader& r, const YAML::Node& n, const std::string& key,
              const Choices<M>& choices) {
  const std::string name = read_string(r, n, key);
  for (const auto& [candidate, value] : choices)
    if (candidate == name) return value;
  r.fail(n, key, "must be one of: " + join(choice_names(choices), ", ") + " (got '" + name + "')");
}

/// An enumerated value written as one of a few words.
template <class T, class M>
Field<T> choice(Doc d, M T::*member, Choices<M> choices) {
  std::string default_text;
  for (const auto& [name, value] : choices)
    if (value == T{}.*member) default_text = name;
  const std::string allowed = join(choice_names(choices), ", ");
  auto read = [member, choices](FileReader& r, const YAML::Node& n, const std::string& key,
                                T& out) { out.*member = read_choice(r, n, key, choices); };
  return {key_doc(d, "word", default_text, allowed), read};
}

/// A list of distinct words, each one of `allowed`.
template <class T>
Field<T> choice_list(Doc d, std::vector<std::string> T::*member, std::vector<std::string> allowed) {
  Choices<std::string> choices;
  for (const auto& name : allowed) choices.emplace_back(name, name);
  auto read = [member, choices](FileReader& r, const YAML::Node& n, const std::string& key,
                                T& out) {
    if (!n.IsSequence()) r.fail(n, key, "expected a list of words (got " + describe(n) + ")");
    std::vector<std::string> values;
    for (std::size_t i = 0; i < n.size(); ++i) {
      const std::string value = read_choice(r, n[i], item_key(key, i), choices);
      if (std::find(values.begin(), values.end(), value) != values.end())
        r.fail(n[i], item_key(key, i), "duplicate entry '" + value + "'");
      values.push_back(value);
    }
    out.*member = std::move(values);
  };
  return {key_doc(d, "list of words", "[" + join(T{}.*member, ", ") + "]",
                  "distinct, each one of " + join(allowed, ", ")),
          read};
}

/// A point [x, y]; `allowed` documents a check made on the merged case.
template <class T>
Field<T> point(Doc d, Vec2 T::*member, std::string allowed) {
  auto read = [member](FileReader& r, const YAML::Node& n, const std::string& key, T& out) {
    out.*member = read_point(r, n, key);
  };
  return {key_doc(d, "[x, y]", format_point(T{}.*member), std::move(allowed)), read};
}

/// A key that must be written; the docs show "required" instead of a default.
template <class T>
Field<T> required(Field<T> field) {
  field.doc.required = true;
  field.doc.default_text = "required";
  return field;
}

/// A nested map merged key by key into member `S T::*`.
template <class T, class S>
Field<T> section(Doc d, S T::*member, const Table<S>& (*table)()) {
  KeyDoc doc = key_doc(d, "map", "see " + table().title, "keys below");
  doc.child = [table] { return section_doc(table()); };
  auto read = [member, table](FileReader& r, const YAML::Node& n, const std::string& key, T& out) {
    parse_map(r, n, key, table(), out.*member);
  };
  return {doc, read};
}

/// A nested map that may be absent. Present, it starts from the inherited one (or from
/// S's defaults) and is merged key by key; null removes an inherited one.
template <class T, class S>
Field<T> optional_section(Doc d, std::optional<S> T::*member, const Table<S>& (*table)()) {
  KeyDoc doc = key_doc(d, "map", "none", "keys below; null removes an inherited one");
  doc.child = [table] { return section_doc(table()); };
  auto read = [member, table](FileReader& r, const YAML::Node& n, const std::string& key, T& out) {
    if (n.IsNull()) {
      (out.*member).reset();
      r.forget(key + ".");
      return;
    }
    S merged = (out.*member).value_or(S{});
    parse_map(r, n, key, table(), merged);
    out.*member = std::move(merged);
  };
  return {doc, read};
}

bool is_identifier_char(char ch) {
  return (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') ||
         ch == '_';
}

/// A name that becomes part of an output column name: non-empty, ASCII letters, digits
/// and '_' only.
template <class T>
Field<T> identifier(Doc d, std::string T::*member) {
  auto read = [member](FileReader& r, const YAML::Node& n, const std::string& key, T& out) {
    const std::string value = read_string(r, n, key);
    if (value.empty()) r.fail(n, key, "must not be empty");
    if (!std::all_of(value.begin(), value.end(), is_identifier_char))
      r.fail(n, key, "may contain only letters, digits and '_' (got '" + value + "')");
    out.*member = value;
  };
  const std::string value = T{}.*member;
  return {key_doc(d, "string", value.empty() ? "(empty)" : "\"" + value + "\"",
                  "non-empty; letters, digits, _"),
          read};
}

// --- Rectangles -------------------------------------------------------------

const Table<Rect>& rect_table() {
  static const Table<Rect> table{
      "Rectangles (`domain.outer`, `domain.inner`, `materials[].box`)",
      "A rectangle is given whole, all four keys, and replaces the previous one; "
      "xmin < xmax and ymin < ymax.",
      {required(number<Rect>({"xmin", "m", "", "left edge"}, &Rect::xmin, any_value())),
       required(number<Rect>({"xmax", "m", "", "right edge"}, &Rect::xmax, any_value())),
       required(number<Rect>({"ymin", "m", "", "bottom edge"}, &Rect::ymin, any_value())),
       required(number<Rect>({"ymax", "m", "", "top edge"}, &Rect::ymax, any_value()))}};
  return table;
}

Rect read_rect(FileReader& r, const YAML::Node& n, const std::string& key) {
  Rect rect;
  r.forget(key + ".");
  parse_map(r, n, key, rect_table(), rect);
  if (!(rect.xmin < rect.xmax))
    r.fail(n["xmax"], key + ".xmax",
           "must be > xmin (got xmin " + format_number(rect.xmin) + ", xmax " +
               format_number(rect.xmax) + ")");
  if (!(rect.ymin < rect.ymax))
    r.fail(n["ymax"], key + ".ymax",
           "must be > ymin (got ymin " + format_number(rect.ymin) + ", ymax " +
               format_number(rect.ymax) + ")");
  return rect;
}


KeyDoc rect_doc(const Doc& d, std::string default_text, std::string allowed) {
  KeyDoc doc = key_doc(d, "rectangle", std::move(default_text), std::move(allowed));
  doc.child = [] { return section_doc(rect_table()); };
  return doc;
}

/// A rectangle; `default_text` replaces the struct default in the docs when that
/// default means "unset" (a material box).
template <class T>
Field<T> rect(Doc d, Rect T::*member, std::string allowed, std::string default_text = "") {
  auto read = [member](FileReader& r, const YAML::Node& n, const std::string& key, T& out) {
    out.*member = read_rect(r, n, key);
  };
  if (default_text.empty()) default_text = format_rect(T{}.*member);
  return {rect_doc(d, std::move(default_text), std::move(allowed)), read};
}

/// A rectangle that may be absent; null removes an inherited one.
template <class T>
Field<T> optional_rect(Doc d, std::optional<Rect> T::*member, std::string allowed) {
  auto read = [member](FileReader& r, const YAML::Node& n, const std::string& key, T& out) {
    if (n.IsNull())
      (out.*member).reset();
    else
      out.*member = read_rect(r, n, key);
  };
  return {rect_doc(d, "none", std::move(allowed)), read};
}

// --- Lists ------------------------------------------------------------------

/// Check of one complete list item (keys present in `seen`), made while reading it.
template <class Item>
using ItemCheck = std::function<void(const FileReader&, const YAML::Node& item,
                                     const std::string& key, const Item&,
                                     const std::set<std::string>& seen)>;

/// A list of maps, replaced as a whole; each item starts from Item's defaults.
template <class T, class Item>
Field<T> map_list(Doc d, std::vector<Item> T::*member, const Table<Item>& (*table)(),
                  std::size_t min_items, std::string default_text,
                  std::type_identity_t<ItemCheck<Item>> check = {}) {
  const std::string allowed =
      min_items > 0 ? "at least " + std::to_string(min_items) + " item" : "any number of items";
  KeyDoc doc = key_doc(d, "list of maps", std::move(default_text), allowed);
  doc.child = [table] { return section_doc(table()); };
  auto read = [member, table, min_items, check](FileReader& r, const YAML::Node& n,
                                                const std::string& key, T& out) {
    if (!n.IsSequence()) r.fail(n, key, "expected a list (got " + describe(n) + ")");
    if (n.size() < min_items)
      r.fail(n, key, "must have at least " + std::to_string(min_items) + " item(s)");
    r.forget(key + "[");
    std::vector<Item> items;
    for (std::size_t i = 0; i < n.size(); ++i) {
      const YAML::Node item_node = n[i];
      const std::string key_i = item_key(key, i);
      r.set_null_line(r.line(n));
      r.record(key_i, item_node);
      Item item{};
      const auto seen = parse_map(r, item_node, key_i, table(), item);
      if constexpr (requires { item.line; }) item.line = r.line(item_node);
      if (check) check(r, item_node, key_i, item, seen);
      items.push_back(std::move(item));
    }
    out.*member = std::move(items);
  };
  return {doc, read};
}

/// fixed_points: a list of [x, y], replaced as a whole.
Field<CaseConfig> fixed_point_list(Doc d) {
  auto read = [](FileReader& r, const YAML::Node& n, const std::string& key, CaseConfig& out) {
    if (!n.IsSequence()) r.fail(n, key, "expected a list of points (got " + describe(n) + ")");
    r.forget(key + "[");
    std::vector<FixedPointConfig> points;
    for (std::size_t i = 0; i < n.size(); ++i) {
      r.set_null_line(r.line(n));
      r.record(item_key(key, i), n[i]);
      points.push_back(FixedPointConfig{read_point(r, n[i], item_key(key, i)), r.line(n[i])});
    }
    out.fixed_points = std::move(points);
  };
  return {key_doc(d, "list of [x, y]", "none", "each inside domain.outer"), read};
}

// --- Sections ---------------------------------------------------------------

const Table<DomainConfig>& domain_table() {
  static const Table<DomainConfig> table{
      "`domain`",
      "",
      {rect({"outer", "m", "§3.1: 100 m x 100 m",
             "outer boundary of the rock; far-field tractions act on its sides"},
            &DomainConfig::outer, "xmin < xmax, ymin < ymax"),
       optional_rect({"inner", "m", "§3.1: 36 m x 24 m; §3.4: 40 m x 40 m",
                      "finer, separately meshed inner domain; null removes an inherited one"},
                     &DomainConfig::inner, "strictly inside outer")}};
  return table;
}

const Table<MeshConfig>& mesh_table() {
  static const Table<MeshConfig> table{
      "`mesh`",
      "`cell_size`, `outer_growth` and `split` apply to structured meshes; `max_area_inner`, "
      "`max_area_outer` and `min_angle` to Delaunay meshes.",
      {choice({"type", "", "§3.1 grid; §3.3, §5.2 constrained Delaunay",
               "structured grid or constrained Delaunay triangulation"},
              &MeshConfig::kind,
              Choices<MeshKind>{{"structured", MeshKind::structured},
                                {"delaunay", MeshKind::delaunay}}),
       number({"cell_size", "m", "§3.1: joints 1 m apart; §3.2: 0.5 to 4 m",
               "side of the square cells inside the inner rectangle"},
              &MeshConfig::cell_size_m, greater_than(0)),
       number({"outer_growth", "-", "§3.1: coarser outer domain",
               "ratio of successive cell sizes from the inner rectangle outwards"},
              &MeshConfig::outer_growth, at_least(1)),
       choice({"split", "", "§3.1: quadrilaterals vs triangles",
               "quadrilateral cells kept whole or split into 2 or 4 triangles"},
              &MeshConfig::split,
              Choices<mesh::CellSplit>{{"none", mesh::CellSplit::none},
                                       {"two", mesh::CellSplit::two},
                                       {"four", mesh::CellSplit::four}}),
       number({"max_area_inner", "m^2", "§3.3: 30 mm^2; §5.2: 2 cm^2",
               "largest triangle area inside the inner rectangle (everywhere without one)"},
              &MeshConfig::max_area_inner_m2, greater_than(0)),
       number({"max_area_outer", "m^2", "§5.5: 50 m^2",
               "largest triangle area outside the inner rectangle"},
              &MeshConfig::max_area_outer_m2, greater_than(0)),
       number({"min_angle", "deg", "", "minimum triangle angle of the Delaunay refinement"},
              &MeshConfig::min_angle_deg, interval(0, true, 30, false))}};
  return table;
}

/// Region 'box' is what a box is for, so each needs the other.
void check_material_item(const FileReader& r, const YAML::Node& item, const std::string& key,
                         const MaterialConfig& material, const std::set<std::string>& seen) {
  if (material.region == "box" && !seen.contains("box"))
    r.fail(item["region"], key + ".region", "region 'box' needs a 'box' rectangle");
  if (material.region != "box" && seen.contains("box"))
    r.fail(item["box"], key + ".box",
           "is only used with region 'box' (region is '" + material.region + "')");
}

const Table<MaterialConfig>& material_table() {
  static const Table<MaterialConfig> table{
      "`materials[]` items",
      "Zones are applied in order; a later zone overrides an earlier one (by block centroid). "
      "`box` is given exactly when `region` is `box`.",
      {text({"name", "", "", "label used in outputs"}, &MaterialConfig::name),
       choice({"region", "", "§3.3: softer outer blocks",
               "where it applies: everywhere, inside or outside domain.inner, or in box"},
              &MaterialConfig::region,
              Choices<std::string>{{"all", "all"}, {"inner", "inner"}, {"outer", "outer"},
                                   {"box", "box"}}),
       rect({"box", "m", "", "zone of region 'box'"}, &MaterialConfig::box,
            "overlaps domain.outer", "none"),
       number({"youngs_modulus", "Pa", "Table 3.1: E = 25 GPa", "Young's modulus"},
              &MaterialConfig::youngs_modulus_Pa, greater_than(0)),
       number({"poissons_ratio", "-", "Table 3.1: nu = 0.25", "Poisson's ratio (plane strain)"},
              &MaterialConfig::poissons_ratio, interval(0, false, 0.5, true)),
       number({"density", "kg/m^3", "Table 3.1: rho_r = 2650 kg/m^3", "rock density"},
              &MaterialConfig::density_kg_m3, greater_than(0))}};
  return table;
}

const Table<JointConfig>& joint_table() {
  static const Table<JointConfig> table{
      "`joints`",
      "Every joint (bond between two blocks) takes these values unless a fracture on it "
      "overrides them.",
      {number({"tensile_strength", "Pa", "Table 3.1: T0 = 0; Table 5.1: T0 = 6 MPa",
               "tensile strength T0 of intact bonds (seed eq. 2.16)"},
              &JointConfig::tensile_strength_Pa, at_least(0)),
       number({"cohesion", "Pa", "Tables 5.1, 5.3: C0",
               "cohesion C0 of intact bonds (seed eq. 2.16)"},
              &JointConfig::cohesion_Pa, at_least(0)),
       number({"friction_angle", "deg", "Table 3.1: phi = 30 deg", "friction angle phi"},
              &JointConfig::friction_angle_deg, interval(0, false, 90, true)),
       boolean({"breakable", "", "§2.3", "false: intact bonds never break"},
               &JointConfig::breakable),
       choice({"breakable_region", "", "§3.4: fracturing in the inner domain only",
               "all, or inner: only joints between two blocks whose centroids lie in domain.inner "
               "may break (a fracture's `breakable` still overrides)"},
              &JointConfig::breakable_region, Choices<std::string>{{"all", "all"}, {"inner", "inner"}})}};
  return table;
}

/// A fracture is a line: its ends must differ. Fluid can only fill joints that start
/// open, and the pressure of fluid-filled joints is solved for, not prescribed. Each
/// flagged value was written in this item (list items start from the defaults).
void check_fracture_item(const FileReader& r, const YAML::Node& item, const std::string& key,
                         const FractureConfig& fracture, const std::set<std::string>&) {
  if (fracture.from == fracture.to)
    r.fail(item["to"], key + ".to",
           "must differ from 'from' (both are " + format_point(fracture.from) + ")");
  if (fracture.fluid_filled && !fracture.initially_open)
    r.fail(item["fluid_filled"], key + ".fluid_filled",
           "fluid_filled: true needs initially_open: true on the same fracture");
  if (fracture.fluid_filled && fracture.pressure_Pa)
    r.fail(item["pressure"], key + ".pressure",
           "cannot be prescribed on a fracture with fluid_filled: true (its pressure is "
           "solved for); give one or the other");
  if (fracture.initial_width_m > 0 && !fracture.fluid_filled)
    r.fail(item["initial_width"], key + ".initial_width",
           "is only used with fluid_filled: true (got " +
               format_number(fracture.initial_width_m) + ")");
}

const Table<FractureConfig>& fracture_table() {
  static const Table<FractureConfig> table{
      "`fractures[]` items",
      "A straight line feature: initial fracture, natural fracture, prescribed path or "
      "interface. Joints lying on it take its values; unset values come from `joints`. "
      "`from` and `to` differ. `fluid_filled: true` needs `initially_open: true` and "
      "excludes `pressure`; `initial_width` > 0 needs `fluid_filled: true`.",
      {text({"name", "", "", "label used in outputs"}, &FractureConfig::name),
       required(point({"from", "m", "§3.1: 20 m fracture at the centre", "first end"},
                      &FractureConfig::from, "inside domain.outer")),
       required(point({"to", "m", "", "second end"}, &FractureConfig::to,
                      "inside domain.outer")),
       number({"segment_length", "m", "§3.1: joints 1 m apart",
               "Delaunay constraint piece length; 0: the mesh size"},
              &FractureConfig::segment_length_m, at_least(0)),
       boolean({"initially_open", "", "§3.2: joints at the injection point start open",
                "bonds on the line are broken at t = 0"},
               &FractureConfig::initially_open),
       boolean({"natural", "", "Tables 5.1, 5.3: natural fractures",
                "pre-existing natural fracture"},
               &FractureConfig::natural),
       optional_boolean({"breakable", "", "§4.5: fracturing confined to one line",
                         "whether its intact bonds may break"},
                        &FractureConfig::breakable, "joints.breakable"),
       optional_number({"tensile_strength", "Pa", "Table 5.1: natural fracture T0 = 0",
                        "tensile strength T0 of its bonds"},
                       &FractureConfig::tensile_strength_Pa, at_least(0),
                       "joints.tensile_strength"),
       optional_number({"cohesion", "Pa", "Table 5.1: natural fracture C0 = 0",
                        "cohesion C0 of its bonds"},
                       &FractureConfig::cohesion_Pa, at_least(0), "joints.cohesion"),
       optional_number({"friction_angle", "deg", "Table 5.1: natural fracture phi = 35 deg",
                        "friction angle of its joints"},
                       &FractureConfig::friction_angle_deg, interval(0, false, 90, true),
                       "joints.friction_angle"),
       optional_number({"pressure", "Pa", "§3.1: 9.81 MPa",
                        "fluid pressure prescribed on its joints"},
                       &FractureConfig::pressure_Pa, at_least(0), "none"),
       boolean({"fluid_filled", "",
                "§3.2: the two fractures on either side of the injection point were "
                "initially opened",
                "its open joints hold fluid (at zero pressure) and belong to the flow "
                "network from t = 0; needs a `fluid` section"},
               &FractureConfig::fluid_filled),
       number({"initial_width", "m", "",
               "initial aperture of its fluid-filled joints; 0: the minimum width "
               "(numerics.min_width_main)"},
              &FractureConfig::initial_width_m, at_least(0), "> 0 only with fluid_filled")}};
  return table;
}

const Table<FluidConfig>& fluid_table() {
  static const Table<FluidConfig> table{
      "`fluid`",
      "Present, the flow network of the fracture joints is solved, coupled with the "
      "blocks; missing keys take the defaults below. Compressible fluid, rho = rho0 (1 + "
      "(p - p0) / K_f) (seed eq. 2.6); cubic law with viscosity mu (eq. 2.2).",
      {number({"density", "kg/m^3", "Table 3.1: rho_f = 1000 kg/m^3",
               "reference density rho0, at the reference pressure"},
              &FluidConfig::density_kg_m3, greater_than(0)),
       number({"bulk_modulus", "Pa", "Table 3.1: K_f = 2.2 GPa",
               "bulk modulus K_f; compressibility c_f = 1 / K_f"},
              &FluidConfig::bulk_modulus_Pa, greater_than(0)),
       number({"viscosity", "Pa s", "Table 3.1: mu = 1 mPa s; Table 5.3: 20 mPa s",
               "dynamic viscosity mu"},
              &FluidConfig::viscosity_Pa_s, greater_than(0)),
       number({"reference_pressure", "Pa", "eq. 2.6: p0",
               "pressure p0 at which the density is rho0"},
              &FluidConfig::reference_pressure_Pa, any_value()),
       number({"leak_off_coefficient", "m/s^0.5", "§3.4: C_L = 0.02 mm/s^0.5 = 2e-5",
               "Carter coefficient C_L of one fracture wall; 0: no leak-off. Both walls "
               "leak: a wetted joint of length L loses 2 C_L L / sqrt(t - t0) per metre of "
               "depth, t0 the time fluid reached it (the seed's eq. 2.3 counts one wall; "
               "NOTES erratum 4)"},
              &FluidConfig::leak_off_coefficient_m_sqrt_s, at_least(0))}};
  return table;
}

const Table<InjectionConfig>& injection_table() {
  static const Table<InjectionConfig> table{
      "`injections[]` items",
      "A fluid source at the mesh vertex nearest `at`; needs a `fluid` section.",
      {text({"name", "", "", "label used in outputs"}, &InjectionConfig::name),
       required(point({"at", "m", "§3.2: injection at the origin",
                       "injection point (the nearest mesh vertex is used)"},
                      &InjectionConfig::at, "inside domain.outer")),
       required(number({"mass_rate", "kg/s", "§3.2: Q0 = 4 kg/s; §3.4: 1 kg/s",
                        "injected mass per second and per metre of out-of-plane thickness"},
                       &InjectionConfig::mass_rate_kg_s, greater_than(0))),
       number({"start_time", "s", "", "time at which injection starts (then continues)"},
              &InjectionConfig::start_time_s, at_least(0))}};
  return table;
}

const Table<ProbeConfig>& probe_table() {
  static const Table<ProbeConfig> table{
      "`probes[]` items",
      "A gauge read at the mesh vertex nearest `at` every step; its pressure is the "
      "history.csv column `probe_<name>_pressure_Pa`, so names are distinct and use "
      "letters, digits and `_` only. Needs a `fluid` section.",
      {required(identifier({"name", "", "", "gauge name, part of the output column names"},
                           &ProbeConfig::name)),
       required(point({"at", "m", "", "gauge location (the nearest mesh vertex is used)"},
                      &ProbeConfig::at, "inside domain.outer"))}};
  return table;
}

const Table<FarFieldConfig>& far_field_table() {
  static const Table<FarFieldConfig> table{
      "`far_field`",
      "Far-field stress, tension positive, applied as tractions t = sigma . n on the listed "
      "sides of `domain.outer` (a 5 MPa compression is `syy: -5e6`).",
      {number({"sxx", "Pa", "Table 5.4: sigma_1, sigma_3", "normal stress along x"},
              &FarFieldConfig::sxx_Pa, any_value()),
       number({"syy", "Pa", "§3.1: 5 MPa background stress", "normal stress along y"},
              &FarFieldConfig::syy_Pa, any_value()),
       number({"sxy", "Pa", "", "shear stress"}, &FarFieldConfig::sxy_Pa, any_value()),
       choice_list({"sides", "", "§3.1: upper and lower boundaries",
                    "sides of domain.outer loaded by the far-field stress"},
                   &FarFieldConfig::sides, {"left", "right", "bottom", "top"}),
       boolean({"in_situ", "", "",
                "the rock starts stressed and in equilibrium (block stresses, joint contact "
                "forces, tractions on all four sides; `sides` is then ignored); false: loaded "
                "by the boundary tractions from rest, as the seed does"},
               &FarFieldConfig::in_situ)}};
  return table;
}

const Table<PointLoadConfig>& point_load_table() {
  static const Table<PointLoadConfig> table{
      "`point_loads[]` items",
      "",
      {point({"at", "m", "", "point of application"}, &PointLoadConfig::at,
             "inside domain.outer"),
       point({"force", "N/m", "", "force per metre of out-of-plane thickness"},
             &PointLoadConfig::force_N_per_m, "any")}};
  return table;
}

const Table<ContactConfig>& contact_table() {
  static const Table<ContactConfig> table{
      "`contact`",
      "Stiffnesses are factors times the largest Young's modulus of the materials.",
      {choice({"method", "", "§2.3: PM or ALM; §3.1: ALM used thereafter",
               "contact enforcement: augmented Lagrangian or penalty"},
              &ContactConfig::method,
              Choices<ContactMethod>{{"alm", ContactMethod::augmented_lagrangian},
                                     {"penalty", ContactMethod::penalty}}),
       number({"normal_stiffness", "-", "Table 3.1: k_n = 100 E; Table 5.1: 30 E",
               "normal spring k_n / max E"},
              &ContactConfig::normal_stiffness_factor, greater_than(0)),
       number({"shear_stiffness", "-", "Table 3.1: k_s = 100 E; Table 5.1: 30 E",
               "shear spring k_s / max E"},
              &ContactConfig::shear_stiffness_factor, greater_than(0)),
       number({"vertex_vertex_activation", "m", "§2.3 item v (cited in §3.1)",
               "tolerance for applying vertex-vertex contacts"},
              &ContactConfig::vertex_vertex_activation_m, at_least(0)),
       number({"fixed_point_stiffness", "-", "§3.3: corners fixed",
               "fixed-point spring / max E"},
              &ContactConfig::fixed_point_stiffness_factor, greater_than(0))}};
  return table;
}

const Table<NumericsConfig>& numerics_table() {
  static const Table<NumericsConfig> table{
      "`numerics`",
      "",
      {choice({"analysis", "", "", "static: velocities reset each step; dynamic: kept"},
              &NumericsConfig::analysis,
              Choices<AnalysisKind>{{"static", AnalysisKind::static_analysis},
                                    {"dynamic", AnalysisKind::dynamic_analysis}}),
       number({"alm_tolerance", "-", "§2.3 (ALM)",
               "ALM stop: max abs(k g) <= tolerance * max abs(contact force)"},
              &NumericsConfig::alm_force_tolerance, greater_than(0)),
       integer({"max_alm_iterations", "", "§2.3 (ALM)", "ALM iterations per open-close pass"},
               &NumericsConfig::max_alm_iterations, at_least(1)),
       integer({"max_open_close_iterations", "", "§2.4: outer iterations",
                "open-close iterations per time step"},
               &NumericsConfig::max_open_close_iterations, at_least(1)),
       number({"tie_tolerance", "-", "§2.3 (iii): 0.1 %",
               "relative difference of normal stress below which simultaneous tensile "
               "failures both break"},
              &NumericsConfig::tie_tolerance, greater_than(0)),
       boolean({"shear_failure_of_intact_joints", "", "§2.3 (ii)",
                "false: intact joints must fail in tension before they may shear"},
               &NumericsConfig::shear_failure_of_intact_joints),
       number({"min_width_main", "m", "§2.1: 0.5 um",
               "smallest aperture of a wetted joint away from the fracture tips"},
              &NumericsConfig::min_width_main_m, greater_than(0), ">= min_width_tip"),
       number({"min_width_tip", "m", "§2.1: 0.1 um",
               "smallest aperture of a wetted joint at a fracture tip"},
              &NumericsConfig::min_width_tip_m, greater_than(0), "<= min_width_main"),
       number({"max_closing_fraction", "-", "§2.1: 5 %",
               "largest fraction of its aperture a wetted joint may close in one step"},
              &NumericsConfig::max_closing_fraction, interval(0, true, 1, true)),
       number({"coupling_tolerance", "-", "§2.4, eqs. 2.25-2.26 (NOTES erratum 2)",
               "coupled-step stop: relative pressure change and relative mass residual "
               "below it"},
              &NumericsConfig::coupling_tolerance, greater_than(0)),
       integer({"max_coupling_iterations", "", "§2.4", "pressure iterations per coupled solve"},
               &NumericsConfig::max_coupling_iterations, at_least(1)),
       integer({"max_step_cuts", "", "",
                "times a step that fails to converge is retried with dt halved before the "
                "run stops"},
               &NumericsConfig::max_step_cuts, at_least(0))}};
  return table;
}

const Table<TimeConfig>& time_table() {
  static const Table<TimeConfig> table{
      "`time`",
      "",
      {number({"dt", "s", "Table 3.1: 1 s; Table 5.3: 1 min", "time step"}, &TimeConfig::dt_s,
              greater_than(0)),
       number({"end_time", "s", "§3.1: 2 steps; Table 4.1: 10 s; Table 5.3: 1 hr",
               "simulated time"},
              &TimeConfig::end_time_s, greater_than(0), ">= time.dt")}};
  return table;
}

const Table<OutputConfig>& output_table() {
  static const Table<OutputConfig> table{
      "`output`",
      "",
      {integer({"every_steps", "", "",
                "joint CSV and VTU every n steps and always at the end; 0: end only"},
               &OutputConfig::every_steps, at_least(0)),
       boolean({"vtu", "", "", "write VTU files"}, &OutputConfig::vtu)}};
  return table;
}

/// `extends` is resolved by the loader before the other keys; here it is only declared.
Field<CaseConfig> extends_key() {
  auto read = [](FileReader&, const YAML::Node&, const std::string&, CaseConfig&) {};
  return {key_doc({"extends", "", "",
                   "base case file, read first; path relative to this file"},
                  "string", "none", "a readable case file, no cycle"),
          read};
}

const Table<CaseConfig>& case_table() {
  static const Table<CaseConfig> table{
      "Top level",
      "",
      {text({"title", "", "", "case title"}, &CaseConfig::title),
       extends_key(),
       section({"domain", "", "", "outer and inner rectangles"}, &CaseConfig::domain,
               &domain_table),
       section({"mesh", "", "", "block mesh"}, &CaseConfig::mesh, &mesh_table),
       map_list({"materials", "", "Tables 3.1, 3.2, 5.1, 5.4: rock parameters",
                 "elastic material zones"},
                &CaseConfig::materials, &material_table, 1,
                "one material with the item defaults", check_material_item),
       section({"joints", "", "Table 3.1: fracture parameters", "default joint strength"},
               &CaseConfig::joints, &joint_table),
       map_list({"fractures", "", "§3.1-3.5, §5.2-5.4", "line features"},
                &CaseConfig::fractures, &fracture_table, 0, "none", check_fracture_item),
       section({"far_field", "", "§3.1: background stress", "far-field stress"},
               &CaseConfig::far_field, &far_field_table),
       map_list({"point_loads", "", "", "concentrated forces"}, &CaseConfig::point_loads,
                &point_load_table, 0, "none"),
       point({"body_force", "N/m^3", "", "body force per unit volume, e.g. [0, -rho g]"},
             &CaseConfig::body_force_N_m3, "any"),
       fixed_point_list({"fixed_points", "m", "§3.3, §5.2: outer boundary fixed at corners",
                         "points held fixed (stiff springs)"}),
       optional_section({"fluid", "", "Table 3.1: fluid parameters",
                         "fracturing fluid; present: the coupled flow network is solved"},
                        &CaseConfig::fluid, &fluid_table),
       map_list({"injections", "", "§3.2: Q0 at the origin", "fluid sources"},
                &CaseConfig::injections, &injection_table, 0, "none"),
       map_list({"probes", "", "", "pressure and aperture gauges"}, &CaseConfig::probes,
                &probe_table, 0, "none"),
       section({"contact", "", "Table 3.1: numerical parameters", "contact model"},
               &CaseConfig::contact, &contact_table),
       section({"numerics", "", "§2.1, §2.3, §2.4", "iterations and tolerances"},
               &CaseConfig::numerics, &numerics_table),
       section({"time", "", "Table 3.1: time step", "time stepping"}, &CaseConfig::time,
               &time_table),
       section({"output", "", "", "what is written"}, &CaseConfig::output, &output_table)}};
  return table;
}

// ---------------------------------------------------------------------------
// Checks on the merged configuration

/// Names the file and line of a key of the merged chain; a key never written (a
/// default) is reported at its closest written parent, else at the top file, line 0.
class MergedChecker {
 public:
  MergedChecker(const Provenance& where, std::string top_file)
      : where_(&where), top_file_(std::move(top_file)) {}

  bool present(const std::string& key) const { return where_->contains(key); }

  [[noreturn]] void fail(const std::string& key, const std::string& rule) const {
    std::string k = key;
    while (!k.empty() && !present(k)) k = parent(k);
    const Location loc = k.empty() ? Location{top_file_, 0} : where_->at(k);
    throw InputError(loc.file, loc.line, key, rule);
  }

 private:
  static std::string parent(const std::string& key) {
    const auto cut = key.find_last_of(".[");
    return cut == std::string::npos ? std::string() : key.substr(0, cut);
  }

  const Provenance* where_;  // not owned
  std::string top_file_;
};

std::string domain_text(const Rect& r) {
  return "[" + format_number(r.xmin) + ", " + format_number(r.xmax) + "] x [" +
         format_number(r.ymin) + ", " + format_number(r.ymax) + "]";
}

void check_point_in_domain(const CaseConfig& c, const MergedChecker& m, const Vec2& p,
                           const std::string& key) {
  if (!c.domain.outer.contains(p))
    m.fail(key, "lies outside the domain " + domain_text(c.domain.outer) + " (got " +
                    format_point(p) + ")");
}

void check_inner_inside_outer(const CaseConfig& c, const MergedChecker& m) {
  if (!c.domain.inner) return;
  const Rect& in = *c.domain.inner;
  const Rect& out = c.domain.outer;
  if (!(in.xmin > out.xmin && in.xmax < out.xmax && in.ymin > out.ymin && in.ymax < out.ymax))
    m.fail("domain.inner", "must lie strictly inside domain.outer " + domain_text(out) +
                               " (got " + domain_text(in) + ")");
}

void check_end_time(const CaseConfig& c, const MergedChecker& m) {
  if (c.time.end_time_s >= c.time.dt_s) return;
  const std::string values = "end_time " + format_number(c.time.end_time_s) + ", dt " +
                             format_number(c.time.dt_s);
  if (m.present("time.end_time") || !m.present("time.dt"))
    m.fail("time.end_time", "must be >= time.dt (got " + values + ")");
  m.fail("time.dt", "must be <= time.end_time (got " + values + "; end_time was not set and "
                    "defaults to " + format_number(TimeConfig{}.end_time_s) + ")");
}

void check_material_regions(const CaseConfig& c, const MergedChecker& m) {
  for (std::size_t i = 0; i < c.materials.size(); ++i) {
    const MaterialConfig& mat = c.materials[i];
    const std::string key = item_key("materials", i);
    if ((mat.region == "inner" || mat.region == "outer") && !c.domain.inner)
      m.fail(key + ".region", "region '" + mat.region + "' needs domain.inner");
    const Rect& b = mat.box;
    const Rect& d = c.domain.outer;
    const bool overlaps = b.xmin < d.xmax && b.xmax > d.xmin && b.ymin < d.ymax && b.ymax > d.ymin;
    if (mat.region == "box" && !overlaps)
      m.fail(key + ".box", "must overlap the domain " + domain_text(d) + " (got " +
                               domain_text(b) + ")");
  }
}

void check_breakable_region(const CaseConfig& c, const MergedChecker& m) {
  if (c.joints.breakable_region == "inner" && !c.domain.inner)
    m.fail("joints.breakable_region", "region 'inner' needs domain.inner");
}

void check_fractures_in_domain(const CaseConfig& c, const MergedChecker& m) {
  for (std::size_t i = 0; i < c.fractures.size(); ++i) {
    check_point_in_domain(c, m, c.fractures[i].from, item_key("fractures", i) + ".from");
    check_point_in_domain(c, m, c.fractures[i].to, item_key("fractures", i) + ".to");
  }
}

void check_points_in_domain(const CaseConfig& c, const MergedChecker& m) {
  for (std::size_t i = 0; i < c.point_loads.size(); ++i)
    check_point_in_domain(c, m, c.point_loads[i].at, item_key("point_loads", i) + ".at");
  for (std::size_t i = 0; i < c.fixed_points.size(); ++i)
    check_point_in_domain(c, m, c.fixed_points[i].at, item_key("fixed_points", i));
  for (std::size_t i = 0; i < c.injections.size(); ++i)
    check_point_in_domain(c, m, c.injections[i].at, item_key("injections", i) + ".at");
  for (std::size_t i = 0; i < c.probes.size(); ++i)
    check_point_in_domain(c, m, c.probes[i].at, item_key("probes", i) + ".at");
}

/// Injections, probes and fluid-filled fractures are parts of the flow network.
void check_fluid_needed(const CaseConfig& c, const MergedChecker& m) {
  if (c.fluid) return;
  const std::string rule = "needs a 'fluid' section (none is given";
  const std::string removed = m.present("fluid") ? "; 'fluid: null' removed it)" : ")";
  if (!c.injections.empty()) m.fail("injections", "a fluid injection " + rule + removed);
  if (!c.probes.empty()) m.fail("probes", "a pressure probe " + rule + removed);
  for (std::size_t i = 0; i < c.fractures.size(); ++i)
    if (c.fractures[i].fluid_filled)
      m.fail(item_key("fractures", i) + ".fluid_filled", "fluid_filled: true " + rule + removed);
}

/// A flow network with no fluid in it and no source would stay empty.
void check_fluid_used(const CaseConfig& c, const MergedChecker& m) {
  if (!c.fluid || !c.injections.empty()) return;
  for (const auto& fracture : c.fractures)
    if (fracture.fluid_filled) return;
  m.fail("fluid", "needs at least one item in 'injections' or one fracture with "
                  "fluid_filled: true (there is neither)");
}

void check_probe_names(const CaseConfig& c, const MergedChecker& m) {
  for (std::size_t i = 0; i < c.probes.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (c.probes[i].name == c.probes[j].name)
        m.fail(item_key("probes", i) + ".name", "duplicate probe name '" + c.probes[i].name +
                                                    "' (also probes[" + std::to_string(j) +
                                                    "]); names must be distinct");
}

void check_min_widths(const CaseConfig& c, const MergedChecker& m) {
  const NumericsConfig& n = c.numerics;
  if (n.min_width_tip_m <= n.min_width_main_m) return;
  const std::string values = "min_width_tip " + format_number(n.min_width_tip_m) +
                             ", min_width_main " + format_number(n.min_width_main_m);
  if (m.present("numerics.min_width_tip") || !m.present("numerics.min_width_main"))
    m.fail("numerics.min_width_tip", "must be <= numerics.min_width_main (got " + values + ")");
  m.fail("numerics.min_width_main",
         "must be >= numerics.min_width_tip (got " + values +
             "; min_width_tip was not set and defaults to " +
             format_number(NumericsConfig{}.min_width_tip_m) + ")");
}

struct CrossCheck {
  std::string rule;  ///< as written in docs/case_file.md
  void (*check)(const CaseConfig&, const MergedChecker&);
};

const std::vector<CrossCheck>& cross_checks() {
  static const std::vector<CrossCheck> checks{
      {"`domain.inner` lies strictly inside `domain.outer`.", check_inner_inside_outer},
      {"`time.end_time` >= `time.dt`.", check_end_time},
      {"A material with region `inner` or `outer` needs `domain.inner`; a material box "
       "overlaps `domain.outer`.",
       check_material_regions},
      {"`joints.breakable_region: inner` needs `domain.inner`.", check_breakable_region},
      {"Both ends of every fracture lie in `domain.outer` (its boundary included).",
       check_fractures_in_domain},
      {"Every point-load location, fixed point, injection point and probe lies in "
       "`domain.outer`.",
       check_points_in_domain},
      {"`injections`, `probes` and a fracture with `fluid_filled: true` need a `fluid` "
       "section.",
       check_fluid_needed},
      {"A `fluid` section needs at least one injection or one fracture with "
       "`fluid_filled: true`.",
       check_fluid_used},
      {"Probe names are distinct.", check_probe_names},
      {"`numerics.min_width_tip` <= `numerics.min_width_main`.", check_min_widths}};
  return checks;
}

// ---------------------------------------------------------------------------
// Files and the extends chain

std::optional<std::string> read_text_file(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) return std::nullopt;
  return text.str();
}

YAML::Node parse_yaml(const std::string& text, const std::string& file) {
  try {
    return YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw InputError(file, e.mark.is_null() ? 0 : e.mark.line + 1, "(syntax)",
                     "YAML syntax error: " + e.msg);
  }
}

/// A file of the extends chain: its label (for messages) and identity (for cycles).
struct ChainEntry {
  std::string id;
  std::string label;
};

std::string file_identity(const std::string& path) {
  std::error_code ec;
  const auto canonical = std::filesystem::weakly_canonical(path, ec);
  return ec ? path : canonical.string();
}

std::string resolve_relative(const std::string& from_file, const std::string& target) {
  const std::filesystem::path path(target);
  if (path.is_absolute()) return path.lexically_normal().string();
  return (std::filesystem::path(from_file).parent_path() / path).lexically_normal().string();
}

void apply_case_text(const std::string& text, const std::string& file,
                     std::vector<ChainEntry>& chain, CaseConfig& config, Provenance& where);

/// Reads the base file named by `extends` into `config` before this file's keys.
void apply_base(FileReader& r, const YAML::Node& node, std::vector<ChainEntry>& chain,
                CaseConfig& config, Provenance& where) {
  const std::string target = read_string(r, node, "extends");
  if (target.empty()) r.fail(node, "extends", "must name a case file (got an empty string)");
  const std::string base = resolve_relative(r.file(), target);
  const std::string id = file_identity(base);
  for (const auto& entry : chain) {
    if (entry.id != id) continue;
    std::vector<std::string> labels;
    for (const auto& e : chain) labels.push_back(e.label);
    labels.push_back(base);
    r.fail(node, "extends", "extends cycle: " + join(labels, " -> "));
  }
  const auto base_text = read_text_file(base);
  if (!base_text) r.fail(node, "extends", "file '" + base + "' cannot be read");
  chain.push_back({id, base});
  apply_case_text(*base_text, base, chain, config, where);
  chain.pop_back();
}

void apply_case_text(const std::string& text, const std::string& file,
                     std::vector<ChainEntry>& chain, CaseConfig& config, Provenance& where) {
  const YAML::Node root = parse_yaml(text, file);
  if (root.IsNull()) return;  // an empty file changes nothing
  FileReader reader(file, where);
  if (root.IsMap()) {
    for (const auto& entry : root) {
      if (!entry.first.IsScalar() || entry.first.Scalar() != "extends") continue;
      reader.set_null_line(reader.line(entry.first));
      apply_base(reader, entry.second, chain, config, where);
      break;  // a second extends is reported as a duplicate key below
    }
  }
  parse_map(reader, root, "", case_table(), config);
}

// ---------------------------------------------------------------------------
// Reference generation

std::string markdown_cell(const std::string& text) {
  std::string cell;
  for (char ch : text) cell += ch == '|' ? std::string("\\|") : std::string(1, ch);
  return cell;
}

void write_section(std::ostringstream& out, const SectionDoc& section,
                   std::set<std::string>& written) {
  if (!written.insert(section.title).second) return;
  out << "\n## " << section.title << "\n\n";
  if (!section.note.empty()) out << section.note << "\n\n";
  out << "| key | type | unit | default | allowed | seed | description |\n"
      << "|---|---|---|---|---|---|---|\n";
  for (const auto& row : section.rows)
    out << "| `" << row.name << "` | " << markdown_cell(row.type) << " | "
        << markdown_cell(row.unit) << " | " << markdown_cell(row.default_text) << " | "
        << markdown_cell(row.allowed) << " | " << markdown_cell(row.seed) << " | "
        << markdown_cell(row.description) << " |\n";
  for (const auto& row : section.rows)
    if (row.child) write_section(out, row.child(), written);
}

constexpr std::string_view kReferenceIntro = R"(# Case file reference

<!-- Generated by hfdda::io::case_file_reference_markdown() from the key tables in
solver/io/case_file.cpp. Do not edit by hand: the unit test
CaseFileDocs.MatchesGeneratedReference fails when this file and the code differ, and
writes the generated text to case_file.md.generated in its working directory. -->

A case file is YAML. Units are SI (m, Pa, kg/m^3, s, N); angles are in degrees;
stresses are tension positive. Every key has the default listed below, except the keys
marked *required*. A complete example is
`solver/tests/data/cases/griffith_seed_3_1.yaml` (seed section 3.1, Table 3.1).

- An unknown key, a key given twice, a value of the wrong type and a value outside its
  allowed range are errors. Each error names the file, the line, the key as a dotted
  path (`materials[1].poissons_ratio`) and the rule broken; nothing is run.
- `extends: base.yaml` reads the base file (path relative to the file that names it)
  before this one; the keys of this file then override it one by one, maps merging
  key by key (`fluid` too; `fluid: null` removes an inherited one). Lists (`materials`,
  `fractures`, `point_loads`, `fixed_points`, `injections`, `probes`,
  `far_field.sides`), points and rectangles are replaced as a whole; list items start
  from the item defaults below. Chains are allowed; a cycle is an error.
- Numbers are plain YAML numbers (`25e9`, `-5.0e6`); a quoted `"25e9"` is a string.
- Checks that need the mesh (a material zone with no block, a degenerate block, a
  fracture off the grid lines of a structured mesh) are made when the model is built.
- Without a `fluid` section no flow network is solved: fluid acts only through the
  pressures prescribed on fractures (`fractures[].pressure`). With one, fluid enters
  through `injections` and fills the joints of fractures marked `fluid_filled`.
)";

/// Where the `mesh` section was last written (the top file, line 0, when it never was),
/// so errors found when the mesh is built can point at it.
void record_mesh_origin(const Provenance& where, CaseConfig& config) {
  const auto it = where.find("mesh");
  config.mesh_file = it != where.end() ? it->second.file : config.file;
  config.mesh.line = it != where.end() ? it->second.line : 0;
}

}  // namespace

std::string case_file_reference_markdown() {
  std::ostringstream out;
  out << kReferenceIntro;
  std::set<std::string> written;
  write_section(out, section_doc(case_table()), written);
  out << "\n## Checks across keys\n\n"
      << "Made after the whole `extends` chain is merged; the error names the file and "
         "line where the offending key was set.\n\n";
  for (const auto& check : cross_checks()) out << "- " << check.rule << "\n";
  return out.str();
}

CaseConfig load_case_text(const std::string& yaml_text, const std::string& file_label) {
  CaseConfig config;
  Provenance where;
  std::vector<ChainEntry> chain{{file_identity(file_label), file_label}};
  apply_case_text(yaml_text, file_label, chain, config, where);
  const MergedChecker checker(where, file_label);
  for (const auto& check : cross_checks()) check.check(config, checker);
  config.file = file_label;
  record_mesh_origin(where, config);
  return config;
}

CaseConfig load_case_file(const std::string& path) {
  const auto text = read_text_file(path);
  if (!text) throw InputError(path, 0, "(file)", "cannot be read");
  return load_case_text(*text, path);
}

}  // namespace hfdda::io
