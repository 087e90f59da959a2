#pragma once
// Field kinds of the case-file key tables: each builds one Field (its docs row and its
// reader) for a member of a config struct. Defaults are not repeated in the tables:
// they are read from the default-constructed struct.

#include <algorithm>
#include <cstddef>
#include <optional>
#include <set>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "io/case_schema.hpp"

namespace hfdda::io::schema {

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
Field<T> integer(Doc d, int T::*member, Range range, std::string also = "") {
  auto read = [member, range](FileReader& r, const YAML::Node& n, const std::string& key, T& out) {
    const int value = read_integer(r, n, key);
    check_range(r, n, key, range, value);
    out.*member = value;
  };
  const std::string allowed = also.empty() ? range.text() : range.text() + ", " + also;
  return {key_doc(d, "integer", std::to_string(T{}.*member), allowed), read};
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

// --- Words ------------------------------------------------------------------

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
  r.fail(n, key, "must be one of: " + join(choice_names(choices), ", ") + " (got '" + clip(name) + "')");
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
        r.fail(n[i], item_key(key, i), "duplicate entry '" + clip(value) + "'");
      values.push_back(value);
    }
    out.*member = std::move(values);
  };
  return {key_doc(d, "list of words", "[" + join(T{}.*member, ", ") + "]",
                  "distinct, each one of " + join(allowed, ", ")),
          read};
}

// --- Points, names, required keys, nested maps ------------------------------

/// A point [x, y]; `allowed` documents a check made on the merged case, or names what
/// `range` applies to (each component).
template <class T>
Field<T> point(Doc d, Vec2 T::*member, std::string allowed, Range range = {}) {
  auto read = [member, range](FileReader& r, const YAML::Node& n, const std::string& key, T& out) {
    const Vec2 p = read_point(r, n, key);
    check_range(r, n, key + "[0]", range, p.x());
    check_range(r, n, key + "[1]", range, p.y());
    out.*member = p;
  };
  if (range.lo || range.hi) allowed += " " + range.rule();
  return {key_doc(d, "[x, y]", format_point(T{}.*member), std::move(allowed)), read};
}

/// A key that must be written; the docs show "required" instead of a default.
template <class T>
Field<T> required(Field<T> field) {
  field.doc.required = true;
  field.doc.default_text = "required";
  return field;
}

/// Check of one complete list item or map (keys present in `seen`), made while reading it.
template <class Item>
using ItemCheck = std::function<void(const FileReader&, const YAML::Node& item,
                                     const std::string& key, const Item&,
                                     const std::set<std::string>& seen)>;

/// A nested map merged key by key into member `S T::*`; `check` sees each written map.
template <class T, class S>
Field<T> section(Doc d, S T::*member, const Table<S>& (*table)(),
                 std::type_identity_t<ItemCheck<S>> check = {}) {
  KeyDoc doc = key_doc(d, "map", "see " + table().title, "keys below");
  doc.child = [table] { return section_doc(table()); };
  auto read = [member, table, check](FileReader& r, const YAML::Node& n, const std::string& key, T& out) {
    const auto seen = parse_map(r, n, key, table(), out.*member);
    if (check) check(r, n, key, out.*member, seen);
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

inline bool is_identifier_char(char ch) {
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
      r.fail(n, key, "may contain only letters, digits and '_' (got '" + clip(value) + "')");
    out.*member = value;
  };
  const std::string value = T{}.*member;
  return {key_doc(d, "string", value.empty() ? "(empty)" : "\"" + value + "\"",
                  "non-empty; letters, digits, _"),
          read};
}

// --- Bond strength: T0 or K_IC ---------------------------------------------

/// `fracture_toughness` of `joints`, a fracture or a pattern: K_IC instead of T0 (`what`
/// completes "K_IC that sets ..."); `fallback` names where an unset value comes from.
template <class T>
Field<T> fracture_toughness_key(const std::string& what, std::optional<double> T::*member,
                                std::string fallback) {
  return optional_number(
      {"fracture_toughness", "Pa m^0.5", "eq. 4.13; §4.5: K_IC = 0.886 and 4.43 MPa m^0.5 (erratum 7)",
       "Mode I toughness K_IC that sets " + what + " joint by joint: T0 = K_IC / sqrt(pi L / 2), "
       "L the joint's length, so the strength follows the mesh and the toughness does not; "
       "excludes tensile_strength in the same map"},
      member, positive_up_to(kMaxStrength), std::move(fallback));
}

/// `tensile_strength` and `fracture_toughness` written in the same map.
inline void check_strength_choice(const FileReader& r, const YAML::Node& map, const std::string& key,
                                  const std::set<std::string>& seen) {
  if (seen.contains("tensile_strength") && seen.contains("fracture_toughness"))
    r.fail(map["fracture_toughness"], child_key(key, "fracture_toughness"),
           "give tensile_strength or fracture_toughness, not both");
}

// --- Rectangles -------------------------------------------------------------

/// The keys of a rectangle (given whole, xmin < xmax and ymin < ymax).
const Table<Rect>& rect_table();

/// Reads a whole rectangle, replacing what `key` held before.
Rect read_rect(FileReader& r, const YAML::Node& n, const std::string& key);

KeyDoc rect_doc(const Doc& d, std::string default_text, std::string allowed);

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

/// Largest number of items of a case-file list (fractures, fixed points, probes, ...).
inline constexpr std::size_t kMaxItems = 10000;

inline void check_item_count(const FileReader& r, const YAML::Node& n, const std::string& key) {
  if (n.size() > kMaxItems)
    r.fail(n, key, "has " + std::to_string(n.size()) + " items; at most " + std::to_string(kMaxItems) +
                       " are allowed");
}

/// A list of maps, replaced as a whole; each item starts from Item's defaults.
template <class T, class Item>
Field<T> map_list(Doc d, std::vector<Item> T::*member, const Table<Item>& (*table)(),
                  std::size_t min_items, std::string default_text,
                  std::type_identity_t<ItemCheck<Item>> check = {}) {
  const std::string allowed = min_items > 0 ? std::to_string(min_items) + " to " + std::to_string(kMaxItems) + " items"
                                            : "at most " + std::to_string(kMaxItems) + " items";
  KeyDoc doc = key_doc(d, "list of maps", std::move(default_text), allowed);
  doc.child = [table] { return section_doc(table()); };
  auto read = [member, table, min_items, check](FileReader& r, const YAML::Node& n,
                                                const std::string& key, T& out) {
    if (!n.IsSequence()) r.fail(n, key, "expected a list (got " + describe(n) + ")");
    if (n.size() < min_items)
      r.fail(n, key, "must have at least " + std::to_string(min_items) + " item(s)");
    check_item_count(r, n, key);
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

}  // namespace hfdda::io::schema
