#include "io/fracture_maps.hpp"

#include <charconv>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <tuple>

#include "core/errors.hpp"
#include "io/case_fields.hpp"
#include "io/case_text.hpp"

namespace hfdda::io {

using namespace schema;

namespace {

const Table<FractureMapConfig>& map_table() {
  using M = FractureMapConfig;
  static const Table<M> table{
      "`fracture_maps[]` items",
      "A CSV file of natural fractures as segments: a header naming `x1,y1,x2,y2` [m] and, "
      "optionally, `set` (a label) and per-row `tensile_strength` [Pa], `cohesion` [Pa], "
      "`friction_angle` [deg], `hydraulic_width` [m], which override the map's values. Every "
      "row becomes a fracture named `<name>.<row>`; on a Delaunay mesh it is a constraint, "
      "crossing segments are split where they meet, ends within `mesh.snap_tolerance` of another "
      "segment or of the domain's side are snapped onto it, and a row reaching past domain.outer keeps "
      "its part inside (summary.json lists what was snapped and cut). Zero-length, duplicate and "
      "wholly outside rows are errors naming the CSV line.",
      {text({"name", "", "", "label of the map; rows are named <name>.<row>"}, &M::name),
       required(Field<M>{key_doc({"file", "", "§5.3: natural fracture networks", "CSV file, relative to the case file"},
                        "string", "none", "a readable CSV file"),
                [](FileReader& r, const YAML::Node& n, const std::string& key, M& out) {
                  out.file = read_string(r, n, key);
                  if (out.file.empty()) r.fail(n, key, "must name a CSV file (got an empty string)");
                  const std::filesystem::path p(out.file);
                  out.path = (p.is_absolute() ? p : std::filesystem::path(r.file()).parent_path() / p)
                                 .lexically_normal()
                                 .string();
                }}),
       boolean({"natural", "", "Tables 5.1, 5.3: natural fractures", "rows are natural fractures"}, &M::natural),
       number({"segment_length", "m", "", "Delaunay mesh: joints along each row no longer than this (0: mesh size)"},
              &M::segment_length_m, at_least(0)),
       optional_boolean({"breakable", "", "", "whether the rows' bonds may break"}, &M::breakable,
                        "joints.breakable"),
       optional_number({"tensile_strength", "Pa", "Table 5.1: T0 = 0", "T0 of the rows' bonds"},
                       &M::tensile_strength_Pa, zero_to(kMaxStrength), "joints.tensile_strength"),
       optional_number({"cohesion", "Pa", "Table 5.1: C0 = 0", "C0 of the rows' bonds"}, &M::cohesion_Pa,
                       zero_to(kMaxStrength), "joints.cohesion"),
       optional_number({"friction_angle", "deg", "Table 5.1: 35 deg", "friction angle of the rows' joints"},
                       &M::friction_angle_deg, interval(0, false, 90, true), "joints.friction_angle"),
       optional_number({"hydraulic_width", "m", "Table 5.1: w0 = 1 um", "w0 of the rows' joints"},
                       &M::hydraulic_width_m, zero_to(kMaxHydraulicWidth), "joints.hydraulic_width")}};
  return table;
}

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, ',')) {
    const auto first = cell.find_first_not_of(" \t\r");
    const auto last = cell.find_last_not_of(" \t\r");
    cells.push_back(first == std::string::npos ? "" : cell.substr(first, last - first + 1));
  }
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

/// The part of segment a-b inside r (Liang and Barsky's parametric clipping), with an end
/// that was cut put exactly on the side that cut it; nullopt when nothing is inside.
std::optional<std::pair<Vec2, Vec2>> clip_to(const Rect& r, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  double t0 = 0.0, t1 = 1.0;
  int side0 = -1, side1 = -1;  // 0 xmin, 1 xmax, 2 ymin, 3 ymax
  const double p[4] = {-d.x(), d.x(), -d.y(), d.y()};
  const double q[4] = {a.x() - r.xmin, r.xmax - a.x(), a.y() - r.ymin, r.ymax - a.y()};
  for (int k = 0; k < 4; ++k) {
    if (p[k] == 0.0) {
      if (q[k] < 0.0) return std::nullopt;  // parallel to this side and outside it
      continue;
    }
    const double t = q[k] / p[k];
    if (p[k] < 0.0 && t > t0) t0 = t, side0 = k;
    if (p[k] > 0.0 && t < t1) t1 = t, side1 = k;
  }
  if (t0 >= t1) return std::nullopt;
  auto on_side = [&](double t, int side) {
    Vec2 x = a + t * d;
    if (side == 0) x.x() = r.xmin;
    if (side == 1) x.x() = r.xmax;
    if (side == 2) x.y() = r.ymin;
    if (side == 3) x.y() = r.ymax;
    return x;
  };
  return std::make_pair(side0 < 0 ? a : on_side(t0, side0), side1 < 0 ? b : on_side(t1, side1));
}

}  // namespace

Field<CaseConfig> fracture_maps_key() {
  return map_list({"fracture_maps", "", "§5.3-5.5: fracture networks",
                   "natural fractures read from CSV files of segments"},
                  &CaseConfig::fracture_maps, &map_table, 0, "none");
}

void append_fracture_map_lines(CaseConfig& config) {
  const Rect& outer = config.domain.outer;
  const double tol = 1e-9 * std::hypot(outer.width(), outer.height());
  for (std::size_t m = 0; m < config.fracture_maps.size(); ++m) {
    const FractureMapConfig& map = config.fracture_maps[m];
    std::ifstream in(map.path, std::ios::binary);
    if (!in) throw InputError(config.file, map.line, item_key("fracture_maps", m) + ".file",
                              "file '" + map.path + "' cannot be read");
    std::string line;
    int line_no = 0;
    std::map<std::string, int> column;
    auto fail = [&](const std::string& key, const std::string& rule) -> void {
      throw InputError(map.path, line_no, key, rule);
    };
    while (line.empty() && std::getline(in, line)) ++line_no;
    if (line.find('\0') != std::string::npos) fail("(header)", "a NUL byte: not a text CSV file");
    const std::vector<std::string> header = split_csv_line(line);
    static const std::set<std::string> known{"x1", "y1", "x2", "y2", "set", "tensile_strength", "cohesion",
                                             "friction_angle", "hydraulic_width"};
    for (std::size_t i = 0; i < header.size(); ++i) {
      if (!known.count(header[i]))
        fail("(header)", "unknown column '" + header[i] +
                             "'; allowed: x1, y1, x2, y2, set, tensile_strength, cohesion, friction_angle, "
                             "hydraulic_width");
      if (!column.emplace(header[i], static_cast<int>(i)).second) fail("(header)", "column '" + header[i] + "' twice");
    }
    for (const char* c : {"x1", "y1", "x2", "y2"})
      if (!column.count(c)) fail("(header)", std::string("missing column '") + c + "' (the header must name x1,y1,x2,y2)");
    std::set<std::tuple<double, double, double, double>> seen;
    std::map<std::tuple<double, double, double, double>, int> first_line;
    int row = 0;
    while (std::getline(in, line)) {
      ++line_no;
      if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
      const std::vector<std::string> cells = split_csv_line(line);
      if (cells.size() != header.size())
        fail("(row)", std::to_string(cells.size()) + " cells, the header has " + std::to_string(header.size()));
      auto number = [&](const std::string& name) -> std::optional<double> {
        const auto it = column.find(name);
        if (it == column.end() || cells[it->second].empty()) return std::nullopt;
        const std::string& text = cells[it->second];
        double v = 0.0;
        const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
        if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(v))
          fail(name, "'" + text + "' is not a finite number");
        return v;
      };
      FractureConfig f;
      ++row;
      f.name = map.name + "." + std::to_string(row);
      for (const char* c : {"x1", "y1", "x2", "y2"})
        if (!number(c)) fail(c, "is empty; every row needs x1, y1, x2, y2");
      f.from = Vec2(*number("x1"), *number("y1"));
      f.to = Vec2(*number("x2"), *number("y2"));
      if ((f.to - f.from).norm() <= tol) fail("x2", "zero-length segment (its ends coincide)");
      if (!outer.contains(f.from, tol) || !outer.contains(f.to, tol)) {
        // A row reaching past the domain keeps its part inside (its end put exactly on the
        // side it crosses); one with nothing inside is an error.
        const double full = (f.to - f.from).norm();
        const std::optional<std::pair<Vec2, Vec2>> inside = clip_to(outer, f.from, f.to);
        if (!inside || (inside->second - inside->first).norm() <= tol)
          fail("x1", "segment outside domain.outer (nothing of it lies inside)");
        std::tie(f.from, f.to) = *inside;
        f.clipped_length_m = full - (f.to - f.from).norm();
      }
      const auto key = f.from.x() < f.to.x() || (f.from.x() == f.to.x() && f.from.y() < f.to.y())
                           ? std::make_tuple(f.from.x(), f.from.y(), f.to.x(), f.to.y())
                           : std::make_tuple(f.to.x(), f.to.y(), f.from.x(), f.from.y());
      if (const auto [it, fresh] = first_line.emplace(key, line_no); !fresh)
        fail("x1", "duplicate of the segment on line " + std::to_string(it->second));
      f.natural = map.natural;
      f.segment_length_m = map.segment_length_m;
      f.breakable = map.breakable;
      f.tensile_strength_Pa = number("tensile_strength") ? number("tensile_strength") : map.tensile_strength_Pa;
      f.cohesion_Pa = number("cohesion") ? number("cohesion") : map.cohesion_Pa;
      f.friction_angle_deg = number("friction_angle") ? number("friction_angle") : map.friction_angle_deg;
      f.hydraulic_width_m = number("hydraulic_width") ? number("hydraulic_width") : map.hydraulic_width_m;
      if (f.tensile_strength_Pa && (*f.tensile_strength_Pa < 0 || *f.tensile_strength_Pa > kMaxStrength))
        fail("tensile_strength", "must be in [0, 1e13] Pa");
      if (f.cohesion_Pa && (*f.cohesion_Pa < 0 || *f.cohesion_Pa > kMaxStrength)) fail("cohesion", "must be in [0, 1e13] Pa");
      if (f.friction_angle_deg && (*f.friction_angle_deg <= 0 || *f.friction_angle_deg >= 90))
        fail("friction_angle", "must be in (0, 90) degrees");
      if (f.hydraulic_width_m && (*f.hydraulic_width_m < 0 || *f.hydraulic_width_m >= kMaxHydraulicWidth))
        fail("hydraulic_width", "must be in [0, 0.01) m");
      f.line = map.line;
      config.fractures.push_back(std::move(f));
    }
    if (row == 0) throw InputError(map.path, line_no, "(rows)", "the map has no segment");
  }
}

}  // namespace hfdda::io
