#include "io/load_ramp_keys.hpp"

#include <cmath>

#include "io/case_fields.hpp"

namespace hfdda::io {

using namespace schema;

namespace {

/// `history`: a list of [t, s] points, replaced as a whole.
Field<LoadRampConfig> history_list(Doc d) {
  auto read = [](FileReader& r, const YAML::Node& n, const std::string& key, LoadRampConfig& out) {
    if (!n.IsSequence()) r.fail(n, key, "expected a list of [t, s] points (got " + describe(n) + ")");
    std::vector<Vec2> points;
    for (std::size_t i = 0; i < n.size(); ++i) {
      const Vec2 p = read_point(r, n[i], item_key(key, i));
      if (p.x() < 0) r.fail(n[i], item_key(key, i), "time must be >= 0 (got " + format_number(p.x()) + ")");
      if (p.x() > kMaxTime || std::abs(p.y()) > kMaxStress)
        r.fail(n[i], item_key(key, i), "must have t <= " + format_number(kMaxTime) + " s and |s| <= " +
                                           format_number(kMaxStress) + " Pa (got " + format_point(p) + ")");
      if (!points.empty() && p.x() <= points.back().x())
        r.fail(n[i], item_key(key, i),
               "times must increase (got " + format_number(p.x()) + " after " + format_number(points.back().x()) + ")");
      points.push_back(p);
    }
    out.history = std::move(points);
  };
  return {key_doc(d, "list of [t, s]", "none", "t in [0, 1e10] and increasing, s in [-1e10, 1e10]; 2 to 100000 points"), read};
}

/// `stop_joints`: names of fractures, breakable patterns or fracture sets.
Field<LoadRampConfig> name_list(Doc d) {
  auto read = [](FileReader& r, const YAML::Node& n, const std::string& key, LoadRampConfig& out) {
    if (!n.IsSequence()) r.fail(n, key, "expected a list of names (got " + describe(n) + ")");
    check_item_count(r, n, key);
    std::vector<std::string> names;
    for (std::size_t i = 0; i < n.size(); ++i) names.push_back(read_string(r, n[i], item_key(key, i)));
    out.stop_joints = std::move(names);
  };
  return {key_doc(d, "list of strings", "none", "names of `fractures`, `breakable_patterns` or `fracture_sets`"),
          read};
}

const Table<LoadRampConfig>& load_ramp_table() {
  static const Table<LoadRampConfig> table{
      "`load_ramp`",
      "Quasi-static loading (seed 4.2-4.4): the far-field traction t = s (sigma . n), sigma = "
      "[[sxx, sxy], [sxy, syy]] per unit of the magnitude s, acts on `sides` in addition to "
      "`far_field`; s is raised level by level, each level one static step of `time.dt` solved "
      "to equilibrium with the failure rules of seed 2.3 (without rule (i), which concerns the "
      "fluid front: a load ramp has no fluid). Levels: `start`, `start + increment`, ... up to "
      "`maximum`, or `history` sampled every `time.dt`. The run ends at the stop condition or "
      "after the last level; `time.end_time` is not used. summary.json reports the level of the "
      "first bond failure and of the stop condition.",
      {number({"sxx", "-", "eq. 4.26: sin^2 beta", "far-field sxx per unit of s"}, &LoadRampConfig::sxx,
              magnitude_up_to(1e3)),
       number({"syy", "-", "§4.2: tension normal to the crack; eq. 4.26: cos^2 beta",
               "far-field syy per unit of s"},
              &LoadRampConfig::syy, magnitude_up_to(1e3)),
       number({"sxy", "-", "§4.3: far-field shear; eq. 4.26: sin beta cos beta", "far-field sxy per unit of s"},
              &LoadRampConfig::sxy, magnitude_up_to(1e3)),
       choice_list({"sides", "", "§4.2: boundaries parallel to the crack", "sides of domain.outer the ramp loads"},
                   &LoadRampConfig::sides, {"left", "right", "bottom", "top"}),
       optional_number({"start", "Pa", "", "magnitude s of the first level"}, &LoadRampConfig::start_Pa,
                       magnitude_up_to(kMaxStress), "0"),
       optional_number({"increment", "Pa", "§4.2: 2 kPa for T0 = 1 MPa, 10 kPa for T0 = 5 MPa",
                        "step of s between levels"},
                       &LoadRampConfig::increment_Pa, positive_up_to(kMaxStress), "none"),
       optional_number({"maximum", "Pa", "", "largest s; the last level"}, &LoadRampConfig::maximum_Pa,
                       magnitude_up_to(kMaxStress), "none"),
       history_list({"history", "s, Pa", "",
                     "piecewise-linear s(t) instead of start/increment/maximum, sampled at t = dt, 2 dt, "
                     "... up to its last time"}),
       boolean({"predict_failures", "", "",
                "uniform ramp: between failures the response is linear, so from two levels without a "
                "failure predict the next one and go on from just below it (2 increments or 1 %, the "
                "larger); from there every level is solved, one increment at a time"},
               &LoadRampConfig::predict_failures),
       choice({"stop_when", "", "§4.2: 75 % of the half-length open; §4.4: first joint failed on both sides",
               "none, broken_fraction or failed_both_sides"},
              &LoadRampConfig::stop_when,
              Choices<std::string>{{"none", "none"},
                                   {"broken_fraction", "broken_fraction"},
                                   {"failed_both_sides", "failed_both_sides"}}),
       name_list({"stop_joints", "", "§4.2, §4.3: the 24 m path each side",
                  "broken_fraction: the joints of these fractures, breakable patterns or fracture sets (a joint on several "
                  "fractures belongs to the last one listed: an open crack written after its path is not part "
                  "of the path)"}),
       number({"stop_fraction", "-", "§4.2, §4.3: 75 %",
               "broken_fraction: stop once the broken length of stop_joints exceeds this fraction of "
               "their length (a bond broken in tension or shear counts)"},
              &LoadRampConfig::stop_fraction, interval(0, true, 1, false)),
       point({"crack_centre", "m", "§4.4: the crack's centre",
              "failed_both_sides: a joint not initially open, fully failed (both ends), whose midpoint "
              "lies on each side of this point along crack_direction"},
             &LoadRampConfig::crack_centre, "inside domain.outer"),
       point({"crack_direction", "-", "", "failed_both_sides: direction of the crack"},
             &LoadRampConfig::crack_direction, "non-zero, each component", magnitude_up_to(1e3))}};
  return table;
}

}  // namespace

Field<CaseConfig> load_ramp_key() {
  Field<CaseConfig> f = optional_section({"load_ramp", "", "§4.2-4.4: stresses incremented until failure",
                                          "quasi-static load ramp with a stop condition"},
                                         &CaseConfig::load_ramp, &load_ramp_table);
  auto read = f.read;
  f.read = [read](FileReader& r, const YAML::Node& n, const std::string& key, CaseConfig& out) {
    read(r, n, key, out);
    if (out.load_ramp) out.load_ramp->line = r.line(n);
  };
  return f;
}

void check_load_ramp(const CaseConfig& c, const MergedChecker& m) {
  if (!c.load_ramp) return;
  const LoadRampConfig& ramp = *c.load_ramp;
  if (ramp.sxx == 0 && ramp.syy == 0 && ramp.sxy == 0)
    m.fail("load_ramp.syy", "the stress pattern sxx, sxy, syy is zero: the ramp would load nothing");
  check_stress_sides(m, "load_ramp", ramp.sxx, ramp.syy, ramp.sxy, ramp.sides, "the ramp's stress pattern");
  if (ramp.history.empty()) {
    if (!ramp.increment_Pa) m.fail("load_ramp.increment", "is required without a history");
    if (!ramp.maximum_Pa) m.fail("load_ramp.maximum", "is required without a history");
    const double start = ramp.start_Pa.value_or(0.0);
    if (*ramp.maximum_Pa < start)
      m.fail("load_ramp.maximum", "must be >= start (got maximum " + format_number(*ramp.maximum_Pa) + ", start " +
                                      format_number(start) + ")");
    const double levels = std::floor((*ramp.maximum_Pa - start) / *ramp.increment_Pa) + 1;
    if (levels > 1.0e6)
      m.fail("load_ramp.increment",
             "gives " + format_number(levels) + " levels from start to maximum; at most 1e6 are allowed");
  } else {
    for (const char* key : {"start", "increment", "maximum"})
      if (m.present(std::string("load_ramp.") + key))
        m.fail(std::string("load_ramp.") + key, "cannot be combined with load_ramp.history (give one or the other)");
    if (ramp.history.size() < 2) m.fail("load_ramp.history", "needs at least 2 points");
    const double steps = ramp.history.back().x() / c.time.dt_s;
    if (steps < 1 || steps > 1.0e6)
      m.fail("load_ramp.history", "lasts " + format_number(ramp.history.back().x()) + " s, " +
                                      format_number(steps) + " steps of time.dt; between 1 and 1e6 are allowed");
  }
  if (ramp.stop_when == "broken_fraction" && ramp.stop_joints.empty())
    m.fail("load_ramp.stop_joints", "stop_when: broken_fraction needs the names of the joints (stop_joints)");
  if (ramp.stop_when != "broken_fraction" && !ramp.stop_joints.empty())
    m.fail("load_ramp.stop_joints", "is only used with stop_when: broken_fraction");
  for (std::size_t i = 0; i < ramp.stop_joints.size(); ++i) {
    const std::string& name = ramp.stop_joints[i];
    bool known = false;
    for (const auto& f : c.fractures) known = known || f.name == name;
    for (const auto& p : c.breakable_patterns) known = known || p.name == name;
    for (const auto& s : c.fracture_sets) known = known || s.name == name;
    if (!known)
      m.fail(item_key("load_ramp.stop_joints", i),
             "names no fracture, breakable pattern or fracture set (got '" + name + "')");
  }
  if (ramp.crack_direction.norm() == 0) m.fail("load_ramp.crack_direction", "must not be [0, 0]");
  if (!c.domain.outer.contains(ramp.crack_centre))
    m.fail("load_ramp.crack_centre", "lies outside the domain " + domain_text(c.domain.outer) + " (got " +
                                         format_point(ramp.crack_centre) + ")");
  if (c.fluid) m.fail("fluid", "cannot be combined with load_ramp (a load ramp is quasi-static mechanics, no fluid)");
  for (std::size_t i = 0; i < c.fractures.size(); ++i)
    if (c.fractures[i].pressure_Pa)
      m.fail(item_key("fractures", i) + ".pressure", "cannot be combined with load_ramp (no fluid in a load ramp)");
  if (m.present("time.end_time"))
    m.fail("time.end_time", "is not used with load_ramp (its levels set the number of steps); remove it");
}

}  // namespace hfdda::io
