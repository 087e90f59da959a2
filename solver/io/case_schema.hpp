#pragma once
// The machinery behind the case-file key tables (internal to the io layer).
//
// A section of a case file is a Table: one Field per key, each holding the key's
// documentation (KeyDoc: the row of docs/case_file.md) and the function that reads and
// validates it. parse_map() walks a YAML map through a table, so parsing, range checks
// and the generated reference all come from the same declaration. The field kinds
// (number, choice, rect, map_list, ...) are in case_fields.hpp.
//
// Errors are InputError(file, line, dotted key, rule); FileReader knows the file and
// records where each key was set, for the checks made after the extends chain is merged.

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/errors.hpp"
#include "core/geometry.hpp"

namespace hfdda::io::schema {

// ---------------------------------------------------------------------------
// Text helpers

/// Shortest text that reads back to v, with YAML-style exponents ("2.5e10", "1e-7").
std::string format_number(double v);
std::string format_point(const Vec2& p);
std::string format_rect(const Rect& r);
std::string join(const std::vector<std::string>& items, const std::string& separator);
/// "prefix.name" (or "name" at the top level).
std::string child_key(const std::string& prefix, const std::string& name);
/// "prefix[index]".
std::string item_key(const std::string& prefix, std::size_t index);
/// `text` cut to `max` characters, "..." marking a cut (values echoed in messages).
std::string clip(std::string_view text, std::size_t max = 80);
/// How a node reads in an error message: "'abc'", "a list", "a map", "null"; quoted
/// scalars say so, because YAML types them as strings.
std::string describe(const YAML::Node& node);

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

double read_number(const FileReader& r, const YAML::Node& node, const std::string& key);
int read_integer(const FileReader& r, const YAML::Node& node, const std::string& key);
bool read_bool(const FileReader& r, const YAML::Node& node, const std::string& key);
std::string read_string(const FileReader& r, const YAML::Node& node, const std::string& key);
Vec2 read_point(const FileReader& r, const YAML::Node& node, const std::string& key);

/// `{youngs_modulus: 1,5}`: in a flow map the comma ends the value, so `5` is read as a
/// key of its own. Called on an unknown key of `map`: refuses it as a decimal comma on
/// the key before it when the unknown key is digits with no value, written right after
/// a comma that follows a whole number. Returns when that is not what happened.
void fail_split_decimal_comma(const FileReader& r, const YAML::Node& map, const YAML::Node& name_node,
                              const std::string& prefix);

// ---------------------------------------------------------------------------
// Plausible bounds of physical parameters (docs/case_file.md, `allowed` column). Far
// beyond any rock, fluid or loading the model is meant for, yet small enough that sums
// and products of them (a stiffness factor times a modulus times a length) stay far
// from overflow, so a typing slip is refused instead of giving NaN coordinates.

inline constexpr double kMaxModulus = 1e13;          ///< Pa: Young's and bulk moduli (diamond: 1.2e12)
/// Pa: Young's modulus. Gelatin, the softest solid fractured in laboratory experiments
/// (dyke and hydraulic-fracture analogues), has 1e3 to 1e4 Pa. The contact springs are
/// factors of it: at 1e-300 Pa their ALM corrections are 1e-297 N and K is not definite.
inline constexpr double kMinYoungsModulus = 1e3;
/// Pa: fluid bulk modulus. A gas at atmospheric pressure has K = p = 1e5 Pa (isothermal),
/// liquids 1e9 to 1e10 Pa; below, the fluid storage term swamps the mass balance.
inline constexpr double kMinFluidBulkModulus = 1e5;
/// Pa s: fluid viscosity, below any gas (hydrogen: 9e-6 Pa s); with no viscosity the
/// cubic-law conductance is unbounded and the mass-balance Jacobian singular.
inline constexpr double kMinViscosity = 1e-6;
/// kg/m^3: fluid density, below any gas at atmospheric pressure (hydrogen: 0.09).
inline constexpr double kMinFluidDensity = 1e-2;
/// Contact and fixed-point springs / max E: a spring softer than the rock lets blocks
/// overlap (or a fixed point drift) by more than their own elastic strain, so the
/// constraint means nothing; the seed uses 30 to 100.
inline constexpr double kMinStiffnessFactor = 1;
inline constexpr double kMaxDensity = 1e5;           ///< kg/m^3 (osmium: 2.3e4)
inline constexpr double kMaxStress = 1e10;           ///< Pa: stresses and pressures
/// Pa (and Pa m^0.5 for a toughness): up to a modulus, so "a strength that never acts"
/// can still be written.
inline constexpr double kMaxStrength = 1e13;
/// m: hydraulic width w0 of closed joints (a 1 cm gap is no longer a closed joint)
inline constexpr double kMaxHydraulicWidth = 1e-2;
inline constexpr double kMaxBodyForce = 1e7;         ///< N/m^3: 1000 g in rock
inline constexpr double kMaxPointForce = 1e12;       ///< N/m: kMaxStress over 100 m
inline constexpr double kMaxStiffnessFactor = 1e6;   ///< contact springs / max E
/// numerics.aperture_response: converged_contacts stiffens the iterated springs this many
/// times for the flow's aperture response: their compliance falls by two orders below
/// what it is at k = 30 E, while k stays far from kMaxStiffnessFactor.
inline constexpr double kConvergedResponseStiffening = 100.0;
inline constexpr double kMaxCoordinate = 1e7;        ///< m: rectangle edges
inline constexpr double kMaxTime = 1e10;             ///< s: about 300 years
inline constexpr double kMaxIterations = 1e6;        ///< iteration counts
inline constexpr double kMaxSteps = 1e7;             ///< time steps of a run
inline constexpr double kMaxCells = 1e7;             ///< cells of a mesh, estimated from sizes
inline constexpr const char* kWithinDomain = "<= the larger side of domain.outer";
inline constexpr const char* kAreaWithinDomain = "<= the area of domain.outer";

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
  std::string text() const;
  /// Completes "must be ...".
  std::string rule() const { return lo && hi ? "in " + text() : text(); }
};

inline Range any_value() { return {}; }
inline Range greater_than(double lo) { return {lo, std::nullopt, true, false}; }
inline Range at_least(double lo) { return {lo, std::nullopt, false, false}; }
inline Range interval(double lo, bool lo_open, double hi, bool hi_open) {
  return {lo, hi, lo_open, hi_open};
}
/// (0, hi]: a positive quantity with a plausible upper bound.
inline Range positive_up_to(double hi) { return interval(0, true, hi, false); }
/// [0, hi].
inline Range zero_to(double hi) { return interval(0, false, hi, false); }
/// [-m, m].
inline Range magnitude_up_to(double m) { return interval(-m, false, m, false); }

void check_range(const FileReader& r, const YAML::Node& node, const std::string& key,
                 const Range& range, double value);

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

/// The descriptive part of a key, written in the tables.
struct Doc {
  std::string name, unit, seed, description;
};

KeyDoc key_doc(const Doc& d, std::string type, std::string default_text, std::string allowed);

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

template <class T>
[[noreturn]] void fail_unknown_key(const FileReader& r, const YAML::Node& name_node,
                                   const std::string& key, const Table<T>& table) {
  std::vector<std::string> names;
  for (const auto& f : table.fields) names.push_back(f.doc.name);
  r.fail(name_node, key, "unknown key; allowed keys: " + join(names, ", "));
}

/// Parses map `node` into `out`: only the keys present override (extends merging).
/// Returns the names present, for checks on a complete item.
template <class T>
std::set<std::string> parse_map(FileReader& r, const YAML::Node& node, const std::string& prefix,
                                const Table<T>& table, T& out) {
  if (!node.IsMap())
    r.fail(node, prefix.empty() ? "(document)" : prefix,
           "expected a map of keys (got " + describe(node) + ")");
  // Before any value is read: the `1` of a split `1,5` may be out of range on its own.
  for (const auto& entry : node) {
    const bool known = entry.first.IsScalar() && std::any_of(table.fields.begin(), table.fields.end(), [&](const auto& f) {
      return f.doc.name == entry.first.Scalar();
    });
    if (!known) fail_split_decimal_comma(r, node, entry.first, prefix);
  }
  std::set<std::string> seen;
  for (const auto& entry : node) {
    const YAML::Node& name_node = entry.first;
    const std::string name = name_node.IsScalar() ? name_node.Scalar() : std::string();
    const std::string key = child_key(prefix, name);
    const Field<T>* field = nullptr;
    for (const auto& f : table.fields)
      if (f.doc.name == name) field = &f;
    if (field == nullptr) fail_unknown_key(r, name_node, key, table);
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

}  // namespace hfdda::io::schema
