// Metrics of the propagation case (seed sections 3.4 and 3.5, Figures 3.13-3.23): the
// seed's descriptions of the fracture patterns turned into numbers, from the committed
// state of the model (the fluid network's wetted joints, the contact states, the block
// corners) and the run's record: which joints are fluid-filled, their extents, branch
// lengths, lengths per orientation and quadrant, mirror symmetry of the joint set, the
// mass ledger, and for the bi-material case the displacement of the two faces of the
// interface. Variants, thresholds and checks are in study.yaml. Writes
// series_<variant>.csv (per step), joints_<variant>.csv (every mesh joint at the end)
// and interface_bimaterial.csv for plot.py.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "dda/block_system.hpp"
#include "fluid/flow_network.hpp"
#include "harness.hpp"
#include "mesh/mesh.hpp"
#include "simulation/snapshots.hpp"
#include "statistics.hpp"

namespace hfdda::verification {
namespace {

constexpr double kTol = 1e-6;  // geometric tolerance on mesh coordinates [m]

struct Sample {
  double time_s = kNaN, wetted = kNaN, pressure = kNaN, aperture = kNaN;
  double xmin = kNaN, xmax = kNaN, ymin = kNaN, ymax = kNaN;
  double injected = kNaN, stored = kNaN, leaked = kNaN, mass_balance_error = kNaN;
  double step_cuts = kNaN, newton = kNaN, step_wall_s = kNaN;
  double ledger = kNaN;  ///< |initial + injected - stored - leaked| / (initial + injected)
};

/// One joint of the mesh at the end of the run (initial mesh coordinates).
struct JointState {
  int id = -1;
  Vec2 p{0, 0}, q{0, 0};
  bool wetted = false, open_p = false, open_q = false, breakable = true, initially_open = false;
  double aperture_p = 0.0, aperture_q = 0.0, tensile_strength = 0.0;
  double length() const { return (q - p).norm(); }
  Vec2 mid() const { return 0.5 * (p + q); }
};

/// What the checks need about the fluid-filled joints at the end of the run.
struct Pattern {
  int wetted = 0;
  double right = 0, left = 0, up = 0, down = 0;         // extents of wetted joints from the origin [m]
  double x_extent() const { return right + left; }
  double y_extent() const { return up + down; }
  double length_total = 0, length_horizontal = 0, length_vertical = 0, length_plus45 = 0, length_minus45 = 0,
         length_other = 0;
  std::array<double, 4> quadrant_length{0, 0, 0, 0};  // wetted length with midpoint in quadrant I..IV
  std::array<double, 4> quadrant_reach{0, 0, 0, 0};   // farthest wetted point (distance from origin)
  int off_y0 = 0;          // wetted joints not on the line y = 0
  int off_axes = 0;        // wetted joints on neither axis
  int outside_inner = 0;   // wetted joints not strictly inside the inner domain
  int unmatched_mirror_x = -1, unmatched_mirror_y = -1, unmatched_swap = -1;  // -1: not computed
  double max_abs_x_on_y0 = 0;  // largest |x| of a wetted joint end on y = 0
};

struct InterfaceFaces {
  int joints = 0;
  double mean_abs_v_upper = kNaN, mean_abs_v_lower = kNaN;
  double mean_v_upper = kNaN, mean_v_lower = kNaN;
  std::vector<std::array<double, 3>> rows;  // x, v_upper, v_lower per joint end
};

std::vector<Sample> samples_of(const simulation::RunRecord& record, double initial_mass) {
  std::vector<Sample> samples;
  for (std::size_t row = 0; row < record.rows(); ++row) {
    auto value = [&](const std::string& name) { return record.value(row, name); };
    Sample s;
    s.time_s = value("time_s");
    s.wetted = value("wetted_joints");
    s.pressure = value("injection_pressure_Pa");
    s.aperture = value("injection_aperture_m");
    s.xmin = value("open_xmin_m");
    s.xmax = value("open_xmax_m");
    s.ymin = value("open_ymin_m");
    s.ymax = value("open_ymax_m");
    s.injected = value("mass_injected_kg");
    s.stored = value("mass_stored_kg");
    s.leaked = value("mass_leaked_kg");
    s.mass_balance_error = value("mass_balance_error");
    s.step_cuts = value("step_cuts");
    s.newton = value("flow_newton_iterations");
    s.step_wall_s = value("step_wall_s");
    // Independent of the solver's own error column: the ledger from the mass columns.
    const double in_system = initial_mass + s.injected;
    s.ledger = in_system > 0.0 ? std::abs(in_system - s.stored - s.leaked) / in_system : kNaN;
    samples.push_back(s);
  }
  return samples;
}

std::string series_csv(const std::vector<Sample>& samples, double initial_mass) {
  std::string text =
      "time_s,wetted_joints,injection_pressure_Pa,injection_aperture_m,open_xmin_m,open_xmax_m,open_ymin_m,"
      "open_ymax_m,mass_initial_kg,mass_injected_kg,mass_stored_kg,mass_leaked_kg,mass_balance_error,"
      "ledger_error,step_cuts,flow_newton_iterations,step_wall_s\n";
  for (const Sample& s : samples) {
    for (double v : {s.time_s, s.wetted, s.pressure, s.aperture, s.xmin, s.xmax, s.ymin, s.ymax, initial_mass,
                     s.injected, s.stored, s.leaked, s.mass_balance_error, s.ledger, s.step_cuts, s.newton})
      text += number(v) + ",";
    text += number(s.step_wall_s) + "\n";
  }
  return text;
}

std::string joints_csv(const std::vector<JointState>& joints) {
  std::string text =
      "id,px,py,qx,qy,wetted,open_p,open_q,aperture_p_m,aperture_q_m,breakable,initially_open,tensile_strength_Pa\n";
  for (const JointState& j : joints)
    text += std::to_string(j.id) + "," + number(j.p.x()) + "," + number(j.p.y()) + "," + number(j.q.x()) + "," +
            number(j.q.y()) + "," + (j.wetted ? "1" : "0") + "," + (j.open_p ? "1" : "0") + "," +
            (j.open_q ? "1" : "0") + "," + number(j.aperture_p) + "," + number(j.aperture_q) + "," +
            (j.breakable ? "1" : "0") + "," + (j.initially_open ? "1" : "0") + "," + number(j.tensile_strength) +
            "\n";
  return text;
}

using Key = std::tuple<long long, long long, long long, long long>;

long long grid(double v) { return std::llround(v / kTol); }

/// Orientation-free key of a segment (end points rounded to kTol).
Key segment_key(const Vec2& a, const Vec2& b) {
  std::pair<long long, long long> u{grid(a.x()), grid(a.y())}, v{grid(b.x()), grid(b.y())};
  if (v < u) std::swap(u, v);
  return {u.first, u.second, v.first, v.second};
}

/// Wetted joints whose image under `map` (about the injection point) is not a wetted joint.
template <class Map>
int unmatched(const std::vector<JointState>& joints, const Vec2& origin, Map map) {
  std::set<Key> wetted;
  for (const JointState& j : joints)
    if (j.wetted) wetted.insert(segment_key(j.p - origin, j.q - origin));
  int count = 0;
  for (const JointState& j : joints)
    if (j.wetted && !wetted.count(segment_key(map(j.p - origin), map(j.q - origin)))) ++count;
  return count;
}

Pattern analyse(const std::vector<JointState>& joints, const Vec2& origin, const Rect& inner, bool structured) {
  Pattern pt;
  for (const JointState& j : joints) {
    if (!j.wetted) continue;
    ++pt.wetted;
    const Vec2 a = j.p - origin, b = j.q - origin, d = b - a;
    const double len = d.norm();
    for (const Vec2& e : {a, b}) {
      pt.right = std::max(pt.right, e.x());
      pt.left = std::max(pt.left, -e.x());
      pt.up = std::max(pt.up, e.y());
      pt.down = std::max(pt.down, -e.y());
    }
    pt.length_total += len;
    if (std::abs(d.y()) <= kTol) pt.length_horizontal += len;
    else if (std::abs(d.x()) <= kTol) pt.length_vertical += len;
    else if (std::abs(std::abs(d.x()) - std::abs(d.y())) <= kTol) (d.x() * d.y() > 0 ? pt.length_plus45 : pt.length_minus45) += len;
    else pt.length_other += len;
    const bool on_y0 = std::abs(a.y()) <= kTol && std::abs(b.y()) <= kTol;
    const bool on_x0 = std::abs(a.x()) <= kTol && std::abs(b.x()) <= kTol;
    if (!on_y0) ++pt.off_y0;
    if (!on_y0 && !on_x0) ++pt.off_axes;
    if (on_y0) pt.max_abs_x_on_y0 = std::max({pt.max_abs_x_on_y0, std::abs(a.x()), std::abs(b.x())});
    const Vec2 m = 0.5 * (a + b);
    if (std::abs(m.x()) > kTol && std::abs(m.y()) > kTol) {
      const int quadrant = m.x() > 0 ? (m.y() > 0 ? 0 : 3) : (m.y() > 0 ? 1 : 2);
      pt.quadrant_length[quadrant] += len;
      pt.quadrant_reach[quadrant] = std::max({pt.quadrant_reach[quadrant], a.norm(), b.norm()});
    }
    const Vec2 mid = j.mid();
    if (!(mid.x() > inner.xmin + kTol && mid.x() < inner.xmax - kTol && mid.y() > inner.ymin + kTol &&
          mid.y() < inner.ymax - kTol))
      ++pt.outside_inner;
  }
  if (structured) {
    pt.unmatched_mirror_x = unmatched(joints, origin, [](const Vec2& v) { return Vec2(-v.x(), v.y()); });
    pt.unmatched_mirror_y = unmatched(joints, origin, [](const Vec2& v) { return Vec2(v.x(), -v.y()); });
    pt.unmatched_swap = unmatched(joints, origin, [](const Vec2& v) { return Vec2(v.y(), v.x()); });
  }
  return pt;
}

/// Vertical displacement of the faces of the wetted interface joints (on y = 0): the
/// block corners at the joint's two points, corner - initial_corner, per side.
InterfaceFaces interface_faces(const simulation::Model& model, const Vec2& origin) {
  InterfaceFaces f;
  const dda::BlockSystem& s = *model.system;
  const mesh::Mesh& m = s.mesh();
  double sum_up = 0, sum_low = 0, abs_up = 0, abs_low = 0;
  int n = 0;
  for (int j = 0; j < static_cast<int>(m.joints.size()); ++j) {
    if (!model.flow->wetted(j)) continue;
    const mesh::Joint& joint = m.joints[j];
    const Vec2 p = m.points[joint.point_p] - origin, q = m.points[joint.point_q] - origin;
    if (std::abs(p.y()) > kTol || std::abs(q.y()) > kTol) continue;
    ++f.joints;
    auto centroid_y = [&](int block) {
      double y = 0;
      for (int k = 0; k < s.n_corners(block); ++k) y += s.initial_corner(block, k).y();
      return y / s.n_corners(block);
    };
    // Block a runs p -> q from corner_a; block b runs q -> p from corner_b.
    const int na = s.n_corners(joint.block_a), nb = s.n_corners(joint.block_b);
    const std::array<int, 2> corners_a{joint.corner_a, (joint.corner_a + 1) % na};  // at p, at q
    const std::array<int, 2> corners_b{(joint.corner_b + 1) % nb, joint.corner_b};  // at p, at q
    const bool a_is_upper = centroid_y(joint.block_a) > centroid_y(joint.block_b);
    for (int end = 0; end < 2; ++end) {
      const double va = s.corner(joint.block_a, corners_a[end]).y() - s.initial_corner(joint.block_a, corners_a[end]).y();
      const double vb = s.corner(joint.block_b, corners_b[end]).y() - s.initial_corner(joint.block_b, corners_b[end]).y();
      const double v_up = a_is_upper ? va : vb, v_low = a_is_upper ? vb : va;
      f.rows.push_back({end == 0 ? p.x() : q.x(), v_up, v_low});
      sum_up += v_up, sum_low += v_low, abs_up += std::abs(v_up), abs_low += std::abs(v_low);
      ++n;
    }
  }
  if (n > 0) {
    f.mean_v_upper = sum_up / n, f.mean_v_lower = sum_low / n;
    f.mean_abs_v_upper = abs_up / n, f.mean_abs_v_lower = abs_low / n;
  }
  std::sort(f.rows.begin(), f.rows.end());
  return f;
}


double max_abs(const std::vector<Sample>& samples, double Sample::*field) {
  return max_abs_finite(samples, [field](const Sample& s) { return s.*field; });
}

double sum(const std::vector<Sample>& samples, double Sample::*field) {
  double total = 0.0;
  for (const Sample& s : samples) total += s.*field;
  return samples.empty() ? kNaN : total;
}

double count(int n) { return n < 0 ? kNaN : double(n); }

void validate(const io::CaseConfig& config, const VariantSpec&) {
  if (!config.fluid || config.injections.size() != 1) throw std::runtime_error("case needs a fluid and one injection");
  if (!config.domain.inner) throw std::runtime_error("case needs an inner domain");
}

/// The committed state of every mesh joint (the last completed step if the run stopped):
/// the library's joint rows (simulation/snapshots.hpp: fluid-filled, contact states,
/// apertures), placed at the joints' initial mesh coordinates (the symmetry keys and the
/// plots need the undeformed pattern; the rows carry the current end points), with the
/// flow network's apertures on fluid-filled joints and the joints' bond properties.
std::vector<JointState> joint_states(const simulation::Model& model) {
  const mesh::Mesh& mesh = model.system->mesh();
  std::vector<JointState> joints;
  for (const io::JointRow& row : simulation::joint_rows(*model.system, model.flow.get())) {
    const mesh::Joint& joint = mesh.joints[row.id];
    JointState js;
    js.id = row.id;
    js.p = mesh.points[joint.point_p];
    js.q = mesh.points[joint.point_q];
    js.wetted = row.fluid;
    js.open_p = row.state_p == dda::to_string(dda::ContactState::open);
    js.open_q = row.state_q == dda::to_string(dda::ContactState::open);
    js.aperture_p = js.wetted ? model.flow->aperture(row.id, 0) : row.aperture_p_m;
    js.aperture_q = js.wetted ? model.flow->aperture(row.id, 1) : row.aperture_q_m;
    js.breakable = joint.properties.breakable;
    js.initially_open = joint.properties.initially_open;
    js.tensile_strength = joint.properties.tensile_strength_Pa;
    joints.push_back(js);
  }
  return joints;
}

/// interface_bimaterial.csv: the displacement of the two faces along the interface.
std::string interface_csv(const InterfaceFaces& faces) {
  std::string text = "x_m,v_upper_m,v_lower_m\n";
  for (const auto& row : faces.rows) text += number(row[0]) + "," + number(row[1]) + "," + number(row[2]) + "\n";
  return text;
}

/// The named numbers the checks refer to: ledger errors, extents, branch lengths and symmetry.
std::map<std::string, double> pattern_numbers(const Pattern& p, const std::vector<Sample>& samples, double leaked) {
  return {
      {"max_mass_balance_error", max_abs(samples, &Sample::mass_balance_error)},
      {"max_ledger_error", max_abs(samples, &Sample::ledger)},
      {"left", p.left},
      {"right", p.right},
      {"up", p.up},
      {"down", p.down},
      {"x_extent", p.x_extent()},
      {"y_extent", p.y_extent()},
      {"half_length", 0.5 * p.x_extent()},
      {"y_minus_new_x", p.y_extent() - (p.x_extent() - 4.0)},
      {"y_over_x", p.y_extent() / p.x_extent()},
      {"min_branch", std::min({p.right, p.left, p.up, p.down})},
      {"max_branch", std::max({p.right, p.left, p.up, p.down})},
      {"mean_branch", 0.25 * (p.right + p.left + p.up + p.down)},
      {"max_abs_x", std::max(p.right, p.left)},
      {"min_vertical_branch", std::min(p.up, p.down)},
      {"shorter_wing", std::min(p.left, p.right)},
      {"min_quadrant_length", *std::min_element(p.quadrant_length.begin(), p.quadrant_length.end())},
      {"minus45_minus_plus45", p.length_minus45 - p.length_plus45},
      {"off_y0_joints", p.off_y0},
      {"off_axes_joints", p.off_axes},
      {"outside_inner_joints", p.outside_inner},
      {"unmatched_mirror_x", count(p.unmatched_mirror_x)},
      {"unmatched_mirrors", count(p.unmatched_mirror_x) + count(p.unmatched_mirror_y)},
      {"unmatched_all", count(p.unmatched_mirror_x) + count(p.unmatched_mirror_y) + count(p.unmatched_swap)},
      {"leaked_kg", leaked},
  };
}

/// result.json: the mass ledger and solver effort over the run.
void ledger_json(nlohmann::json& m, const std::vector<Sample>& samples) {
  m["max_mass_balance_error"] = finite_or_null(max_abs(samples, &Sample::mass_balance_error));
  m["max_ledger_error"] = finite_or_null(max_abs(samples, &Sample::ledger));
  m["step_cuts_total"] = finite_or_null(sum(samples, &Sample::step_cuts));
  m["flow_newton_iterations_total"] = finite_or_null(sum(samples, &Sample::newton));
  m["max_step_wall_s"] = finite_or_null(max_abs(samples, &Sample::step_wall_s));
}

/// result.json: extents, lengths per orientation and quadrant, and symmetry of the wetted joints.
void pattern_json(nlohmann::json& m, const Pattern& p, bool structured) {
  m["wetted_joints"] = p.wetted;
  m["extent_m"] = {{"left", p.left}, {"right", p.right}, {"down", p.down}, {"up", p.up}};
  m["wetted_length_m"] = {{"total", p.length_total},       {"horizontal", p.length_horizontal},
                          {"vertical", p.length_vertical}, {"plus45", p.length_plus45},
                          {"minus45", p.length_minus45},   {"other", p.length_other}};
  m["quadrant_length_m"] = p.quadrant_length;
  m["quadrant_reach_m"] = p.quadrant_reach;
  m["off_y0_joints"] = p.off_y0;
  m["off_axes_joints"] = p.off_axes;
  m["outside_inner_joints"] = p.outside_inner;
  if (structured)
    m["unmatched"] = {{"mirror_x", p.unmatched_mirror_x}, {"mirror_y", p.unmatched_mirror_y},
                      {"swap_xy", p.unmatched_swap}};
}

/// result.json: the state at the last recorded step.
void at_end_json(nlohmann::json& m, const std::vector<Sample>& samples) {
  if (samples.empty()) return;
  const Sample& e = samples.back();
  m["at_end"] = {{"time_s", e.time_s},
                 {"injection_pressure_Pa", e.pressure},
                 {"injection_aperture_m", e.aperture},
                 {"open_extent_m", {e.xmin, e.xmax, e.ymin, e.ymax}},
                 {"injected_kg", e.injected},
                 {"stored_kg", e.stored},
                 {"leaked_kg", e.leaked}};
}

/// result.json: the two faces of the interface (bi-material case).
nlohmann::json interface_json(const InterfaceFaces& faces) {
  return {{"wetted_joints", faces.joints},
          {"mean_abs_v_upper_m", finite_or_null(faces.mean_abs_v_upper)},
          {"mean_abs_v_lower_m", finite_or_null(faces.mean_abs_v_lower)},
          {"mean_v_upper_m", finite_or_null(faces.mean_v_upper)},
          {"mean_v_lower_m", finite_or_null(faces.mean_v_lower)}};
}

std::string summary_line(int blocks, const Pattern& p, const std::vector<Sample>& samples) {
  char line[200];
  std::snprintf(line, sizeof line, "blocks %4d  wetted %3d  x %+6.2f..%+6.2f  y %+6.2f..%+6.2f  mass %.1e", blocks,
                p.wetted, -p.left, p.right, -p.down, p.up, max_abs(samples, &Sample::mass_balance_error));
  return line;
}

Metrics variant_metrics(const VariantRun& r) {
  Metrics out;
  nlohmann::json& m = out.json;
  const std::string& name = r.variant->name;
  m["blocks"] = r.model ? r.model->system->n_blocks() : 0;
  m["joints"] = r.model ? static_cast<int>(r.model->system->mesh().joints.size()) : 0;
  if (!r.model) {
    if (name == "bimaterial") out.files["interface_bimaterial.csv"] = "x_m,v_upper_m,v_lower_m\n";
    out.numbers["max_mass_balance_error"] = kNaN;
    return out;
  }
  const simulation::Model& model = *r.model;
  const Rect inner = *r.config->domain.inner;
  const Vec2 origin = model.system->mesh().points[model.injection_points.at(0)];
  const double initial_mass = model.flow->initial_mass();

  // The committed state (the last completed step if the run stopped).
  const std::vector<JointState> joints = joint_states(model);
  const bool structured = r.variant->flag("structured");
  const Pattern p = analyse(joints, origin, inner, structured);
  const std::vector<Sample> samples = samples_of(r.record(), initial_mass);
  const double leaked = model.flow->leaked_mass();
  out.files["joints_" + name + ".csv"] = joints_csv(joints);
  out.files["series_" + name + ".csv"] = series_csv(samples, initial_mass);

  InterfaceFaces faces;
  if (name == "bimaterial") {
    faces = interface_faces(model, origin);
    out.files["interface_bimaterial.csv"] = interface_csv(faces);
  }

  out.numbers = pattern_numbers(p, samples, leaked);
  if (name == "bimaterial") out.numbers["opening_ratio"] = faces.mean_abs_v_lower / faces.mean_abs_v_upper;

  ledger_json(m, samples);
  pattern_json(m, p, structured);
  m["leaked_kg"] = leaked;
  m["initial_mass_kg"] = initial_mass;
  at_end_json(m, samples);
  if (name == "bimaterial") m["interface"] = interface_json(faces);
  out.summary = summary_line(model.system->n_blocks(), p, samples);
  return out;
}

/// Comparisons between variants: with case (a) at dsigma = 0 (its half-length, NaN when
/// it did not complete or did not run) and with case (a) at dsigma = 5 MPa, dt = 1 s.
void study_metrics(StudyOutcome& s) {
  const VariantOutcome* free_s0 = s.find("free_s0");
  const double free_half_length =
      free_s0 && free_s0->run.completed ? 0.5 * free_s0->metrics.numbers.at("x_extent") : kNaN;
  const VariantOutcome* free_s5 = s.find("free_s5");
  const bool reference = free_s5 && free_s5->run.completed;
  for (VariantOutcome& v : s.variants) {
    if (!v.run.built) continue;
    auto& n = v.metrics.numbers;
    const std::string& name = v.variant().name;
    if (name == "cross_s0") n["max_branch_over_free_half_length"] = n.at("max_branch") / free_half_length;
    if (name == "leakoff_s0") n["half_length_over_free"] = n.at("half_length") / free_half_length;
    if (name == "free_s5_dt05" || name == "free_s5_dt2") {
      double difference = kNaN;
      if (reference) {
        const auto& q = free_s5->metrics.numbers;
        difference = std::max({std::abs(n.at("left") - q.at("left")), std::abs(n.at("right") - q.at("right")),
                               std::abs(n.at("up") - q.at("up")), std::abs(n.at("down") - q.at("down"))});
      }
      n["extent_difference_from_dt1"] = difference;
    }
  }
}

}  // namespace

CaseDefinition case_definition() { return {validate, variant_metrics, study_metrics}; }

}  // namespace hfdda::verification
