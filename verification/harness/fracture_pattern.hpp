#pragma once
// Measures of a fracture pattern at the end of a run, shared by the network cases
// (seed 5.3-5.4): which joints are open, invaded or natural, the extents of the open and
// invaded sets along the axes, and the joints a figure draws. Coordinates are those of
// the initial mesh (the pattern, not the displaced rock).
//
// Definitions (seed 5.3, Figures 5.10-5.16): a joint is open when at least one of its
// end contacts is open (the rock has separated: the hydraulic fracture propagated along
// it); invaded when the flow network has wetted it (fluid reached it, open or not).

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "dda/block_system.hpp"
#include "fluid/flow_network.hpp"
#include "mesh/mesh.hpp"
#include "harness.hpp"
#include "simulation/model.hpp"

namespace hfdda::verification {

struct JointPattern {
  std::vector<char> open, invaded, natural;
  std::vector<double> length_m;
  std::vector<Vec2> p, q;  ///< end points (initial mesh)
};

inline JointPattern joint_pattern(const simulation::Model& model) {
  const dda::BlockSystem& s = *model.system;
  const auto& joints = s.mesh().joints;
  const auto& points = s.mesh().points;
  JointPattern jp;
  const std::size_t n = joints.size();
  jp.open.assign(n, 0), jp.invaded.assign(n, 0), jp.natural.assign(n, 0), jp.length_m.assign(n, 0.0);
  jp.p.resize(n), jp.q.resize(n);
  for (std::size_t j = 0; j < n; ++j) {
    const int ji = static_cast<int>(j);
    jp.open[j] = s.joint_end_state(ji, 0) == dda::ContactState::open || s.joint_end_state(ji, 1) == dda::ContactState::open;
    jp.invaded[j] = model.flow && model.flow->wetted(ji);
    jp.natural[j] = joints[j].properties.natural;
    jp.p[j] = points[joints[j].point_p];
    jp.q[j] = points[joints[j].point_q];
    jp.length_m[j] = (jp.q[j] - jp.p[j]).norm();
  }
  return jp;
}

/// Range (max - min) of the end points' coordinate `axis` (0: x, 1: y) over the joints
/// selected by `mask`; NaN when none is selected.
inline double extent_m(const JointPattern& jp, const std::vector<char>& mask, int axis) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (std::size_t j = 0; j < mask.size(); ++j)
    if (mask[j]) lo = std::min({lo, jp.p[j][axis], jp.q[j][axis]}), hi = std::max({hi, jp.p[j][axis], jp.q[j][axis]});
  return hi >= lo ? hi - lo : std::numeric_limits<double>::quiet_NaN();
}

/// Total length of the joints with mask[j] && (filter[j] == want) [m]; filter may be empty.
inline double length_where(const JointPattern& jp, const std::vector<char>& mask,
                           const std::vector<char>* filter = nullptr, bool want = true) {
  double sum = 0.0;
  for (std::size_t j = 0; j < mask.size(); ++j)
    if (mask[j] && (!filter || bool((*filter)[j]) == want)) sum += jp.length_m[j];
  return sum;
}

/// The measures of one run's pattern, as named numbers for the checks and JSON for
/// result.json: open and invaded lengths and extents, the open band's aspect (x-extent
/// over y-extent), the share of the open length on natural fractures.
inline void measure_pattern(const JointPattern& jp, Metrics& m) {
  const double open_m = length_where(jp, jp.open);
  const double open_natural_m = length_where(jp, jp.open, &jp.natural, true);
  std::vector<char> closed_invaded_natural(jp.open.size(), 0);
  for (std::size_t j = 0; j < jp.open.size(); ++j)
    closed_invaded_natural[j] = jp.invaded[j] && !jp.open[j] && jp.natural[j];
  const double open_x = extent_m(jp, jp.open, 0), open_y = extent_m(jp, jp.open, 1);
  m.numbers["open_length_m"] = open_m;
  m.numbers["open_natural_fraction"] = open_m > 0.0 ? open_natural_m / open_m : std::numeric_limits<double>::quiet_NaN();
  m.numbers["open_x_extent_m"] = open_x;
  m.numbers["open_y_extent_m"] = open_y;
  m.numbers["open_band_aspect"] = open_y > 0.0 ? open_x / open_y : std::numeric_limits<double>::quiet_NaN();
  m.numbers["invaded_length_m"] = length_where(jp, jp.invaded);
  m.numbers["invaded_closed_natural_m"] = length_where(jp, closed_invaded_natural);
  m.numbers["invaded_x_extent_m"] = extent_m(jp, jp.invaded, 0);
  m.numbers["invaded_y_extent_m"] = extent_m(jp, jp.invaded, 1);
  m.numbers["natural_length_m"] = length_where(jp, jp.natural);
  for (const char* key : {"open_length_m", "open_natural_fraction", "open_x_extent_m", "open_y_extent_m",
                          "open_band_aspect", "invaded_length_m", "invaded_closed_natural_m", "invaded_x_extent_m",
                          "invaded_y_extent_m", "natural_length_m"})
    m.json[key] = finite_or_null(m.numbers[key]);
}

/// The joints a figure draws (natural, open or invaded), as CSV: px,py,qx,qy,natural,open,invaded.
inline std::string pattern_csv(const JointPattern& jp) {
  std::ostringstream out;
  out.precision(9);
  out << "px,py,qx,qy,natural,open,invaded\n";
  for (std::size_t j = 0; j < jp.open.size(); ++j) {
    if (!jp.natural[j] && !jp.open[j] && !jp.invaded[j]) continue;
    out << jp.p[j].x() << ',' << jp.p[j].y() << ',' << jp.q[j].x() << ',' << jp.q[j].y() << ',' << int(jp.natural[j])
        << ',' << int(jp.open[j]) << ',' << int(jp.invaded[j]) << '\n';
  }
  return out.str();
}

/// Open joints of a run from its joints CSV (pattern_csv): end-point text -> length [m].
/// The variants of one network share their mesh, so equal text is the same joint.
inline std::map<std::string, double> open_joints_of(const Metrics& m, const std::string& variant) {
  std::map<std::string, double> open;
  const auto file = m.files.find("joints_" + variant + ".csv");
  if (file == m.files.end()) return open;
  std::istringstream in(file->second);
  std::string line;
  std::getline(in, line);  // header: px,py,qx,qy,natural,open,invaded
  while (std::getline(in, line)) {
    std::istringstream row(line);
    std::string field[7];
    for (auto& f : field) std::getline(row, f, ',');
    if (field[5] != "1") continue;
    const double dx = std::stod(field[2]) - std::stod(field[0]), dy = std::stod(field[3]) - std::stod(field[1]);
    open[field[0] + ',' + field[1] + ',' + field[2] + ',' + field[3]] = std::hypot(dx, dy);
  }
  return open;
}

/// Length-weighted Jaccard index of two open sets, |A and B| / |A or B|; NaN if both are empty.
inline double open_jaccard(const std::map<std::string, double>& a, const std::map<std::string, double>& b) {
  double both = 0.0, either = 0.0;
  for (const auto& [key, length] : a) {
    either += length;
    if (b.count(key)) both += length;
  }
  for (const auto& [key, length] : b)
    if (!a.count(key)) either += length;
  return either > 0.0 ? both / either : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace hfdda::verification
