// Metrics of Blanton's interaction experiments (seed 5.2, Tables 5.1-5.2, Figure 5.4):
// the interaction mode of each run, decided by the rule of README.md from the committed
// state at the end of the run, the lengths behind it (natural fracture opened, invaded,
// slipped; rock broken beyond it), and the interaction map of the sweep. Variants,
// thresholds and checks are in study.yaml. Writes modes.csv (one row per run) and
// joints_<variant>.csv (the joints that matter for the figures) for plot.py.

#include <algorithm>
#include <limits>
#include <map>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>
#include <vector>
#include <stdexcept>
#include <string>

#include "analytical/interaction_criteria.hpp"
#include "dda/block_system.hpp"
#include "fluid/flow_network.hpp"
#include "harness.hpp"
#include "mesh/mesh.hpp"
#include "statistics.hpp"

namespace hfdda::verification {
namespace {

/// README, "Mode rule": a broken rock joint counts as beyond the natural fracture when
/// both of its ends are at least this far on the far side of the fracture's line.
constexpr double kBeyondDistance_m = 1.0e-3;
/// README, "Mode rule": the natural fracture counts as opened when its open joints add up
/// to at least this fraction of the distance from the injection point to it.
constexpr double kOpeningFraction = 0.5;

/// A number for the report's table, with a fixed number of decimals.
std::string format_fixed(double v, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, v);
  return text;
}

enum class Mode { crossing = 0, opening = 1, arrest = 2, none = 3 };

const char* to_string(Mode m) {
  switch (m) {
    case Mode::crossing: return "crossing";
    case Mode::opening: return "opening";
    case Mode::arrest: return "arrest";
    case Mode::none: return "none";
  }
  return "none";
}

Mode mode_of_text(const std::string& text) {
  for (Mode m : {Mode::crossing, Mode::opening, Mode::arrest, Mode::none})
    if (text == to_string(m)) return m;
  throw std::runtime_error("unknown interaction mode '" + text + "' (crossing, opening, arrest)");
}

/// The natural fracture's line and the injection point, from the case file.
struct Geometry {
  Vec2 injection{0, 0};
  Vec2 crossing{0, 0};      ///< where the natural fracture meets the path of the hydraulic fracture
  Vec2 direction{1, 0};     ///< unit vector along the natural fracture
  double angle_deg = 0.0;   ///< approach angle to the x axis, in (0, 90]
  /// From the injection point to where the natural fracture crosses the path (the mode
  /// rule's length scale, README: 4 cm).
  double distance_m = 0.0;
  /// Signed distance from the natural fracture's line, positive on the far side.
  double beyond(const Vec2& p) const {
    const Vec2 normal(direction.y(), -direction.x());
    const double side = (injection - crossing).dot(normal) > 0 ? -1.0 : 1.0;
    return side * (p - crossing).dot(normal);
  }
};

Geometry geometry_of(const io::CaseConfig& c) {
  if (c.injections.size() != 1) throw std::runtime_error("the case needs one injection point");
  Geometry g;
  g.injection = c.injections.front().at;
  bool found = false;
  for (const io::FractureConfig& f : c.fractures) {
    if (!f.natural) continue;
    const Vec2 d = (f.to - f.from).normalized();
    if (found && std::abs(d.x() * g.direction.y() - d.y() * g.direction.x()) > 1e-9)
      throw std::runtime_error("the natural fracture's pieces must lie on one line");
    g.direction = d.y() < 0 ? Vec2(-d) : d;
    // The crossing with the x axis (the path of the hydraulic fracture, y = 0).
    if (std::abs(g.direction.y()) < 1e-12) throw std::runtime_error("the natural fracture must cross y = 0");
    g.crossing = Vec2(f.from.x() - f.from.y() * g.direction.x() / g.direction.y(), 0.0);
    found = true;
  }
  if (!found) throw std::runtime_error("the case has no natural fracture");
  g.angle_deg = std::atan2(g.direction.y(), std::abs(g.direction.x())) * 180.0 / std::numbers::pi;
  g.distance_m = (g.crossing - g.injection).norm();
  return g;
}

void validate(const io::CaseConfig& c, const VariantSpec& v) {
  const Geometry g = geometry_of(c);
  if (std::abs(g.angle_deg - v.number("theta_deg")) > 1e-6)
    throw std::runtime_error("the natural fracture lies at " + std::to_string(g.angle_deg) +
                             " degrees, the variant says theta_deg = " + v.text("theta_deg"));
  if (std::abs(-c.far_field.sxx_Pa - v.number("sigma_max_Pa")) > 1.0 ||
      std::abs(-c.far_field.syy_Pa - v.number("sigma_min_Pa")) > 1.0 || c.far_field.sxy_Pa != 0.0)
    throw std::runtime_error("far_field must be sxx = -sigma_max_Pa, syy = -sigma_min_Pa, sxy = 0 of the variant");
  if (!c.far_field.in_situ) throw std::runtime_error("far_field must be in_situ (the block starts under its stress)");
}

/// What the mode rule reads from the end of a run.
struct Interaction {
  double beyond_m = 0.0;           ///< broken rock joints entirely beyond the natural fracture
  double natural_opened_m = 0.0;   ///< natural-fracture joints with an open end
  double natural_invaded_m = 0.0;  ///< natural-fracture joints holding fluid
  double natural_slipped_m = 0.0;  ///< natural-fracture joints with a broken bond and no open end
  double natural_failed_m = 0.0;   ///< natural-fracture joints with a broken bond or open end
  double rock_broken_m = 0.0;      ///< rock joints broken during the run
  double max_shear_slip_m = 0.0;   ///< largest tangential offset of the faces of a slipped natural joint
  bool reached = false;            ///< the fluid or a failure reached the natural fracture
  Mode mode = Mode::none;
};

/// Tangential offset of the two faces of a joint at one end: block a's corner against
/// block b's, along the joint's initial direction [m].
double face_slip(const dda::BlockSystem& s, const mesh::Joint& j, int end) {
  const int n_a = s.n_corners(j.block_a), n_b = s.n_corners(j.block_b);
  const int corner_a = end == 0 ? j.corner_a : (j.corner_a + 1) % n_a;
  const int corner_b = end == 0 ? (j.corner_b + 1) % n_b : j.corner_b;
  const Vec2 along = (s.mesh().points[j.point_q] - s.mesh().points[j.point_p]).normalized();
  return std::abs((s.corner(j.block_a, corner_a) - s.corner(j.block_b, corner_b)).dot(along));
}

Interaction interaction_of(const simulation::Model& model, const Geometry& g) {
  const dda::BlockSystem& s = *model.system;
  const auto& points = s.mesh().points;
  const auto& contacts = s.contacts();
  Interaction in;
  for (int j = 0; j < static_cast<int>(s.mesh().joints.size()); ++j) {
    const mesh::Joint& joint = s.mesh().joints[j];
    const auto ends = s.joint_contacts(j);
    const bool open = s.joint_end_state(j, 0) == dda::ContactState::open ||
                      s.joint_end_state(j, 1) == dda::ContactState::open;
    const bool broken = !contacts[ends[0]].bonded || !contacts[ends[1]].bonded;
    const bool wetted = model.flow && model.flow->wetted(j);
    const double length = (points[joint.point_q] - points[joint.point_p]).norm();
    if (joint.properties.natural) {
      in.natural_opened_m += open ? length : 0.0;
      in.natural_invaded_m += wetted ? length : 0.0;
      in.natural_failed_m += (open || broken) ? length : 0.0;
      if (broken && !open) {
        in.natural_slipped_m += length;
        in.max_shear_slip_m = std::max({in.max_shear_slip_m, face_slip(s, joint, 0), face_slip(s, joint, 1)});
      }
      in.reached = in.reached || open || broken || wetted;
    } else if (broken && !joint.properties.initially_open) {
      in.rock_broken_m += length;
      if (std::min(g.beyond(points[joint.point_p]), g.beyond(points[joint.point_q])) >= kBeyondDistance_m)
        in.beyond_m += length;
    }
  }
  if (in.beyond_m > 0.0) in.mode = Mode::crossing;
  else if (in.natural_opened_m >= kOpeningFraction * g.distance_m) in.mode = Mode::opening;
  else if (in.reached) in.mode = Mode::arrest;
  else in.mode = Mode::none;
  return in;
}

Metrics variant_metrics(const VariantRun& r) {
  Metrics m;
  const VariantSpec& v = *r.variant;
  m.json["theta_deg"] = v.number("theta_deg");
  m.json["delta_sigma_MPa"] = (v.number("sigma_max_Pa") - v.number("sigma_min_Pa")) / 1e6;
  if (!r.built || !r.model || !r.config) return m;
  const Geometry g = geometry_of(*r.config);
  // The natural fracture as the mesh holds it: the length of its joints against the
  // length of the line features that define it (a fracture map must land on joints).
  double natural_joints_m = 0.0, natural_features_m = 0.0;
  for (const mesh::Joint& joint : r.model->system->mesh().joints)
    if (joint.properties.natural)
      natural_joints_m += (r.model->system->mesh().points[joint.point_q] - r.model->system->mesh().points[joint.point_p]).norm();
  for (const io::FractureConfig& f : r.config->fractures)
    if (f.natural) natural_features_m += (f.to - f.from).norm();
  m.numbers["natural_length_error"] = std::abs(natural_joints_m - natural_features_m) / natural_features_m;
  m.json["natural_joints_m"] = natural_joints_m;
  const Interaction in = interaction_of(*r.model, g);
  m.numbers["mode_code"] = static_cast<double>(in.mode);
  m.numbers["natural_opened_m"] = in.natural_opened_m;
  m.numbers["natural_invaded_m"] = in.natural_invaded_m;
  m.numbers["natural_slipped_m"] = in.natural_slipped_m;
  m.numbers["rock_beyond_m"] = in.beyond_m;
  m.numbers["stopped_at_edge"] = r.run.stop_reason == "fluid_at_edge" ? 1.0 : 0.0;
  if (v.has("blanton_mode")) m.numbers["mode_matches"] = in.mode == mode_of_text(v.text("blanton_mode")) ? 1.0 : 0.0;
  m.json["mode"] = to_string(in.mode);
  m.json["natural_opened_m"] = in.natural_opened_m;
  m.json["natural_invaded_m"] = in.natural_invaded_m;
  m.json["natural_slipped_m"] = in.natural_slipped_m;
  m.json["natural_failed_m"] = in.natural_failed_m;
  m.json["max_shear_slip_m"] = in.max_shear_slip_m;
  m.json["rock_broken_m"] = in.rock_broken_m;
  m.json["rock_beyond_m"] = in.beyond_m;
  m.json["distance_to_natural_m"] = g.distance_m;
  m.json["stop_reason"] = r.run.stop_reason;
  // Net pressure at the injection point at the end of the run (Warpinski and Teufel's p - sigma_h).
  if (r.record().rows() > 0) {
    const double net = r.record().series("injection_pressure_Pa").back() - v.number("sigma_min_Pa");
    m.numbers["net_pressure_Pa"] = net;
    m.json["net_pressure_Pa"] = net;
  }
  m.json["time_s"] = r.run.time_s;

  // The joints the figures draw: natural, broken, invaded (initial coordinates).
  std::ostringstream joints;
  joints << "px,py,qx,qy,natural,open,broken,invaded\n";
  const dda::BlockSystem& s = *r.model->system;
  for (int j = 0; j < static_cast<int>(s.mesh().joints.size()); ++j) {
    const mesh::Joint& joint = s.mesh().joints[j];
    const auto ends = s.joint_contacts(j);
    const bool open = s.joint_end_state(j, 0) == dda::ContactState::open ||
                      s.joint_end_state(j, 1) == dda::ContactState::open;
    const bool broken = !s.contacts()[ends[0]].bonded || !s.contacts()[ends[1]].bonded;
    const bool invaded = r.model->flow && r.model->flow->wetted(j);
    if (!joint.properties.natural && !broken && !invaded) continue;
    const Vec2& p = s.mesh().points[joint.point_p];
    const Vec2& q = s.mesh().points[joint.point_q];
    joints << p.x() << ',' << p.y() << ',' << q.x() << ',' << q.y() << ',' << joint.properties.natural << ','
           << open << ',' << broken << ',' << invaded << '\n';
  }
  m.files["joints_" + v.name + ".csv"] = joints.str();
  m.summary = std::string("mode ") + to_string(in.mode) + (v.has("blanton_mode") ? " (Blanton: " + v.text("blanton_mode") + ")" : "");
  return m;
}

/// The analytical criteria over the map (docs/interaction_criteria.md): their boundaries
/// for criteria.csv and where the simulated modes agree with them. Warpinski and Teufel
/// take the median net pressure of the eleven tests at the end of their runs.
void compare_with_criteria(StudyOutcome& st) {
  const double mu = std::tan(35.0 * std::numbers::pi / 180.0), t0 = 6.0e6, sigma_h = 5.0e6;  // Table 5.1, the map
  std::vector<double> nets;
  for (const VariantOutcome& o : st.variants)
    if (o.variant().has("group") && o.variant().text("group") == "test" && o.metrics.numbers.count("net_pressure_Pa"))
      nets.push_back(o.metrics.numbers.at("net_pressure_Pa"));
  if (nets.empty()) return;
  std::sort(nets.begin(), nets.end());
  const double net = nets[nets.size() / 2];
  const double rp = analytical::renshaw_pollard_critical_differential_stress(sigma_h, t0, mu);
  std::ostringstream csv;
  csv << "criterion,theta_deg,delta_sigma_MPa\n";
  char label[128];
  std::snprintf(label, sizeof label, "Warpinski-Teufel opening below (net %.2g MPa)", net / 1e6);
  for (int theta = 30; theta <= 90; ++theta)
    csv << label << ',' << theta << ','
        << analytical::warpinski_teufel_opening_differential_stress(theta * std::numbers::pi / 180.0, net) / 1e6 << '\n';
  std::snprintf(label, sizeof label, "Warpinski-Teufel slip below (net %.2g MPa)", net / 1e6);
  for (int theta = 30; theta <= 90; ++theta) {
    double boundary = kNaN;  // largest differential stress (0-20 MPa) at which it still slips
    for (double ds = 0.0; ds <= 20e6; ds += 0.05e6)
      if (analytical::warpinski_teufel_slips(theta * std::numbers::pi / 180.0, ds, sigma_h, net, mu, 0.0)) boundary = ds;
    if (std::isfinite(boundary) && boundary < 20e6) csv << label << ',' << theta << ',' << boundary / 1e6 << '\n';
  }
  csv << "Renshaw-Pollard crossing above (90 deg)," << 90 << ',' << rp / 1e6 << '\n';
  std::map<int, double> gw_by_theta;  // Gu-Weng crossing stress per whole degree (infinite: never below 40 MPa)
  for (int theta = 30; theta <= 90; ++theta) {
    const auto c = analytical::gu_weng_critical_differential_stress(theta * std::numbers::pi / 180.0, sigma_h, t0, mu, 40e6);
    gw_by_theta[theta] = c ? *c : std::numeric_limits<double>::infinity();
    if (c && *c <= 20e6) csv << "Gu-Weng crossing above," << theta << ',' << *c / 1e6 << '\n';
  }
  st.metrics.files["criteria.csv"] = csv.str();

  int at_90 = 0, rp_agree = 0, map_runs = 0, wt_agree = 0, gw_runs = 0, gw_agree = 0;
  nlohmann::json disagree = nlohmann::json::array();
  for (const VariantOutcome& o : st.variants) {
    const VariantSpec& v = o.variant();
    if (!v.has("group") || v.text("group") != "map" || !o.metrics.json.contains("mode")) continue;
    const std::string mode = o.metrics.json["mode"];
    const double theta = v.number("theta_deg");
    const double ds = v.number("sigma_max_Pa") - v.number("sigma_min_Pa");
    ++map_runs;
    const bool wt_opens = ds < analytical::warpinski_teufel_opening_differential_stress(theta * std::numbers::pi / 180.0, net);
    if (wt_opens == (mode == "opening")) ++wt_agree;
    else disagree.push_back(v.name + ": " + mode + ", Warpinski-Teufel " + (wt_opens ? "opening" : "no opening"));
    const auto gw = gw_by_theta.find(static_cast<int>(std::lround(theta)));
    if (gw != gw_by_theta.end()) {
      ++gw_runs;
      const bool gw_crosses = ds > gw->second;
      if (gw_crosses == (mode == "crossing")) ++gw_agree;
      else disagree.push_back(v.name + ": " + mode + ", Gu-Weng " + (gw_crosses ? "crossing" : "no crossing"));
    }
    if (theta == 90.0) {
      ++at_90;
      const bool rp_crosses = ds > rp;
      if (rp_crosses == (mode == "crossing")) ++rp_agree;
      else disagree.push_back(v.name + ": " + mode + ", Renshaw-Pollard " + (rp_crosses ? "crossing" : "no crossing"));
    }
  }
  st.metrics.json["criteria"] = {{"net_pressure_Pa", net},
                                 {"renshaw_pollard_critical_differential_stress_Pa", rp},
                                 {"renshaw_pollard_agree", rp_agree},
                                 {"renshaw_pollard_runs", at_90},
                                 {"warpinski_teufel_opening_agree", wt_agree},
                                 {"warpinski_teufel_opening_runs", map_runs},
                                 {"gu_weng_agree", gw_agree},
                                 {"gu_weng_runs", gw_runs},
                                 {"disagreements", disagree}};
  st.metrics.numbers["renshaw_pollard_agreement"] = at_90 ? double(rp_agree) / at_90 : kNaN;
  st.metrics.numbers["warpinski_teufel_opening_agreement"] = map_runs ? double(wt_agree) / map_runs : kNaN;
  st.metrics.numbers["gu_weng_agreement"] = gw_runs ? double(gw_agree) / gw_runs : kNaN;
}

void study_metrics(StudyOutcome& st) {
  std::ostringstream modes;
  modes << "variant,group,test_id,theta_deg,sigma_max_MPa,sigma_min_MPa,delta_sigma_MPa,mode,blanton_mode,seed_mode,"
           "natural_opened_m,natural_invaded_m,natural_slipped_m,rock_beyond_m,time_s,wall_s\n";
  int tests = 0, matched = 0;
  double tests_wall_s = 0.0, map_wall_s = 0.0;
  // The report's table of the eleven tests: Blanton's mode, the seed's and this run's.
  nlohmann::json test_rows = nlohmann::json::array();
  int table_matched = 0;
  auto cm = [](double metres) { return std::isfinite(metres) ? format_fixed(100.0 * metres, 1) : std::string("-"); };
  for (VariantOutcome& o : st.variants) {
    const VariantSpec& v = o.variant();
    const std::string group = v.has("group") ? v.text("group") : "test";
    auto number = [&](const char* name) {
      const auto it = o.metrics.numbers.find(name);
      return it == o.metrics.numbers.end() ? kNaN : it->second;
    };
    const std::string mode = o.metrics.json.contains("mode") ? o.metrics.json["mode"].get<std::string>() : "none";
    if (group == "test") {
      ++tests;
      matched += number("mode_matches") == 1.0;
      tests_wall_s += o.run.run.wall_seconds;
    } else if (group == "map") {
      map_wall_s += o.run.run.wall_seconds;
    }
    if (group == "test" || group == "quick") {
      const std::string blanton = v.has("blanton_mode") ? v.text("blanton_mode") : "";
      const std::string test = (v.has("test_id") ? v.text("test_id") : v.name) +
                               (v.name.find("map") != std::string::npos ? " (fracture map)" : "");
      test_rows.push_back({test, format_fixed(v.number("theta_deg"), 0),
                           format_fixed(v.number("sigma_max_Pa") / 1e6, 0) + " / " +
                               format_fixed(v.number("sigma_min_Pa") / 1e6, 0),
                           blanton, v.has("seed_mode") ? v.text("seed_mode") : "",
                           mode == blanton ? mode : "**" + mode + "** (missed)",
                           cm(number("natural_opened_m")) + " / " + cm(number("natural_invaded_m")) + " / " +
                               cm(number("natural_slipped_m")),
                           format_fixed(o.run.run.wall_seconds, 1)});
      table_matched += mode == blanton;
    }
    char row[512];
    std::snprintf(row, sizeof row, "%s,%s,%s,%g,%g,%g,%g,%s,%s,%s,%g,%g,%g,%g,%g,%g\n", v.name.c_str(), group.c_str(),
                  v.has("test_id") ? v.text("test_id").c_str() : "", v.number("theta_deg"),
                  v.number("sigma_max_Pa") / 1e6, v.number("sigma_min_Pa") / 1e6,
                  (v.number("sigma_max_Pa") - v.number("sigma_min_Pa")) / 1e6, mode.c_str(),
                  v.has("blanton_mode") ? v.text("blanton_mode").c_str() : "",
                  v.has("seed_mode") ? v.text("seed_mode").c_str() : "", number("natural_opened_m"),
                  number("natural_invaded_m"), number("natural_slipped_m"), number("rock_beyond_m"), o.run.run.time_s,
                  o.run.run.wall_seconds);
    modes << row;
    // Same mode as another run (the dt = 0.25 s runs against their dt = 0.5 s test).
    if (v.has("same_mode_as")) {
      const VariantOutcome* other = st.find(v.text("same_mode_as"));
      if (other && other->metrics.json.contains("mode") && o.metrics.json.contains("mode"))
        o.metrics.numbers["same_mode"] = other->metrics.json["mode"] == o.metrics.json["mode"] ? 1.0 : 0.0;
    }
  }
  st.metrics.numbers["tests"] = tests;
  st.metrics.numbers["modes_matched"] = matched;
  st.metrics.numbers["tests_wall_s"] = tests_wall_s;
  st.metrics.numbers["map_wall_s"] = map_wall_s;
  st.metrics.json["modes_matched"] = matched;
  st.metrics.json["tests"] = tests;
  if (!test_rows.empty())
    st.metrics.tables.push_back(
        {{"title", "Blanton's tests: his mode, the seed's and this run's (" + std::to_string(table_matched) + " of " +
                       std::to_string(test_rows.size()) + " matched)"},
         {"header", {"test", "theta [deg]", "sigma_max / sigma_min [MPa]", "Blanton", "seed", "HFDDA",
                     "natural fracture opened / invaded / slipped [cm]", "wall [s]"}},
         {"rows", test_rows}});
  st.metrics.json["tests_wall_s"] = tests_wall_s;
  st.metrics.json["map_wall_s"] = map_wall_s;
  st.metrics.files["modes.csv"] = modes.str();
  compare_with_criteria(st);
}

}  // namespace

CaseDefinition case_definition() { return {validate, variant_metrics, study_metrics}; }

}  // namespace hfdda::verification
