// Verification driver: fracture propagation in symmetric and asymmetric media
// (seed sections 3.4 and 3.5, Figures 3.13-3.23).
//
//   verify_propagation --tier quick|full --case-dir DIR --out RESULT_DIR
//
// Runs the case variants through the library's public API (simulation::build_model,
// simulation::run), then reads the committed state of the model (the fluid network's
// wetted joints, the contact states, the block corners) and the run's history.csv, and
// turns the seed's descriptions of the fracture patterns into numbers: which joints are
// fluid-filled, their extents, branch lengths, lengths per orientation and quadrant,
// mirror symmetry of the joint set, the mass ledger, and for the bi-material case the
// displacement of the two faces of the interface. Writes RESULT_DIR/result.json (schema
// in verification/README.md), series_<variant>.csv (per step), joints_<variant>.csv
// (every mesh joint at the end, for the figures), interface_bimaterial.csv and the run
// directories under runs/. A variant whose case cannot be built, whose run stops or
// throws, or whose history.csv lacks a column is reported as such (its checks fail,
// the values are those of the last committed step); the driver goes on.
// Exit code: 0 when every gating check matches its expectation, 1 otherwise, 2 on a
// usage or driver error.

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "dda/block_system.hpp"
#include "fluid/flow_network.hpp"
#include "io/case_config.hpp"
#include "io/output.hpp"
#include "mesh/mesh.hpp"
#include "simulation/model.hpp"
#include "simulation/run.hpp"

#include "driver_support.hpp"

namespace {

using hfdda::verification::Check;
using hfdda::verification::finite_or_null;
using hfdda::verification::number;

using namespace hfdda;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kTol = 1e-6;  // geometric tolerance on mesh coordinates [m]

struct Variant {
  std::string name;        // run directory and file-name tag
  std::string case_file;   // in the case directory
  std::string label;       // for the report
  std::string seed;        // seed figure
  bool structured;         // structured 2 m grid (symmetry checks apply)
  bool quick;              // part of the quick (CI) tier
};

const std::vector<Variant> kVariants{
    {"free_s0", "base.yaml", "(a) free propagation, dsigma = 0", "3.4, Fig. 3.13 A", true, true},
    {"free_s5", "free_s5.yaml", "(a) free propagation, dsigma = 5 MPa", "3.4, Fig. 3.13 B", true, true},
    {"cross_s0", "cross_s0.yaml", "(b) cross-shaped start, dsigma = 0", "3.4, Fig. 3.14 A", true, false},
    {"cross_s5", "cross_s5.yaml", "(b) cross-shaped start, dsigma = 5 MPa", "3.4, Fig. 3.14 B", true, false},
    {"diagonal_s0", "diagonal_s0.yaml", "(c) diagonal-only, dsigma = 0", "3.4, Fig. 3.15 A", true, false},
    {"diagonal_s5", "diagonal_s5.yaml", "(c) diagonal-only, dsigma = 5 MPa", "3.4, Fig. 3.15 B", true, false},
    {"leakoff_s0", "leakoff_s0.yaml", "(d) leak-off C_L = 0.02 mm/s^0.5, dsigma = 0", "3.4, Figs. 3.16-3.17",
     true, false},
    {"weak_diagonal", "weak_diagonal.yaml", "(e) diagonal-only, -45 deg joints weaker, dsigma = 0",
     "3.5, Figs. 3.18-3.19", true, true},
    {"delaunay", "delaunay.yaml", "(f) Delaunay mesh, dsigma = 0", "3.5, Fig. 3.20", false, false},
    {"bimaterial", "bimaterial.yaml", "(g) bi-material interface, dsigma = 0", "3.5, Figs. 3.21-3.23", true,
     false},
    // Beyond the seed: the hardest pattern (turning) at two other time steps.
    {"free_s5_dt05", "free_s5_dt05.yaml", "(a) free propagation, dsigma = 5 MPa, dt = 0.5 s", "3.4 (time step)",
     true, false},
    {"free_s5_dt2", "free_s5_dt2.yaml", "(a) free propagation, dsigma = 5 MPa, dt = 2 s", "3.4 (time step)", true,
     false},
};

const std::vector<std::string> kRequiredColumns{
    "time_s",         "wetted_joints",      "injection_pressure_Pa", "injection_aperture_m", "open_xmin_m",
    "open_xmax_m",    "open_ymin_m",        "open_ymax_m",           "mass_injected_kg",     "mass_stored_kg",
    "mass_leaked_kg", "mass_balance_error", "step_cuts",             "flow_newton_iterations", "step_wall_s"};

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

struct VariantResult {
  Variant variant;
  bool built = false, completed = false, history_ok = false;
  std::string message;
  int blocks = 0, joints = 0;
  double initial_mass = kNaN, leaked_mass = kNaN;
  Vec2 origin{0, 0};
  Rect inner;
  simulation::RunResult run;
  std::vector<Sample> samples;
  std::vector<JointState> joint_states;
  Pattern pattern;
  InterfaceFaces faces;

  void note(const std::string& text) { message += (message.empty() ? "" : "; ") + text; }
  double max_over(double Sample::*field) const {
    if (!history_ok || samples.empty()) return kNaN;
    double e = 0.0;
    for (const Sample& s : samples) {
      if (!std::isfinite(s.*field)) return kNaN;
      e = std::max(e, std::abs(s.*field));
    }
    return e;
  }
  double sum_over(double Sample::*field) const {
    double total = 0.0;
    for (const Sample& s : samples) total += s.*field;
    return samples.empty() ? kNaN : total;
  }
  bool has_pattern() const { return built; }
};

std::vector<Sample> read_history(const std::string& path, double initial_mass) {
  const verification::CsvTable table = verification::CsvTable::read(path, kRequiredColumns);
  std::vector<Sample> samples;
  for (std::size_t row = 0; row < table.rows(); ++row) {
    auto value = [&](const std::string& name) { return table.value(row, name); };
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

void write_series(const std::string& path, const std::vector<Sample>& samples, double initial_mass) {
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
  io::write_file_atomically(path, text);
}

void write_joints(const std::string& path, const std::vector<JointState>& joints) {
  std::string text =
      "id,px,py,qx,qy,wetted,open_p,open_q,aperture_p_m,aperture_q_m,breakable,initially_open,tensile_strength_Pa\n";
  for (const JointState& j : joints)
    text += std::to_string(j.id) + "," + number(j.p.x()) + "," + number(j.p.y()) + "," + number(j.q.x()) + "," +
            number(j.q.y()) + "," + (j.wetted ? "1" : "0") + "," + (j.open_p ? "1" : "0") + "," +
            (j.open_q ? "1" : "0") + "," + number(j.aperture_p) + "," + number(j.aperture_q) + "," +
            (j.breakable ? "1" : "0") + "," + (j.initially_open ? "1" : "0") + "," + number(j.tensile_strength) +
            "\n";
  io::write_file_atomically(path, text);
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

VariantResult run_variant(const Variant& v, const std::string& case_dir, const std::string& out_dir,
                          const std::string& tier) {
  VariantResult r;
  r.variant = v;
  const std::string run_dir = out_dir + "/runs/" + v.name;
  std::filesystem::remove_all(run_dir);  // never read a previous run's output
  for (const char* prefix : {"series_", "joints_"}) std::filesystem::remove(out_dir + "/" + prefix + v.name + ".csv");
  simulation::Model model;
  try {
    const io::CaseConfig config = io::load_case_file(case_dir + "/" + v.case_file);
    if (!config.fluid || config.injections.size() != 1) throw std::runtime_error("case needs a fluid and one injection");
    if (!config.domain.inner) throw std::runtime_error("case needs an inner domain");
    r.inner = *config.domain.inner;
    model = simulation::build_model(config);
    r.built = true;
    r.blocks = model.system->n_blocks();
    r.joints = static_cast<int>(model.system->mesh().joints.size());
    r.origin = model.system->mesh().points[model.injection_points.at(0)];
    r.initial_mass = model.flow->initial_mass();
    r.run = simulation::run(model, {run_dir, true, tier == "full"});
    r.completed = r.run.completed;
    if (!r.completed) r.note("run stopped at t = " + number(r.run.time_s) + " s: " + r.run.message);
  } catch (const std::exception& e) {
    r.note(std::string(r.built ? "run failed: " : "case not built: ") + e.what());
  }
  if (!r.built) return r;
  // The committed state (the last completed step if the run stopped).
  const dda::BlockSystem& s = *model.system;
  const mesh::Mesh& m = s.mesh();
  for (int j = 0; j < static_cast<int>(m.joints.size()); ++j) {
    JointState js;
    js.id = j;
    js.p = m.points[m.joints[j].point_p];
    js.q = m.points[m.joints[j].point_q];
    js.wetted = model.flow->wetted(j);
    js.open_p = s.contacts()[2 * j].state == dda::ContactState::open;
    js.open_q = s.contacts()[2 * j + 1].state == dda::ContactState::open;
    js.aperture_p = js.wetted ? model.flow->aperture(j, 0) : std::max(0.0, s.joint_gap(j, 0));
    js.aperture_q = js.wetted ? model.flow->aperture(j, 1) : std::max(0.0, s.joint_gap(j, 1));
    js.breakable = m.joints[j].properties.breakable;
    js.initially_open = m.joints[j].properties.initially_open;
    js.tensile_strength = m.joints[j].properties.tensile_strength_Pa;
    r.joint_states.push_back(js);
  }
  r.leaked_mass = model.flow->leaked_mass();
  r.pattern = analyse(r.joint_states, r.origin, r.inner, v.structured);
  if (v.name == "bimaterial") r.faces = interface_faces(model, r.origin);
  write_joints(out_dir + "/joints_" + v.name + ".csv", r.joint_states);
  try {
    r.samples = read_history(run_dir + "/history.csv", r.initial_mass);
    r.history_ok = true;
    write_series(out_dir + "/series_" + v.name + ".csv", r.samples, r.initial_mass);
  } catch (const std::exception& e) {
    r.note(e.what());
  }
  return r;
}


}  // namespace

int main(int argc, char** argv) {
  const auto options = verification::parse_driver_options(argc, argv, "verify_propagation");
  if (!options) return 2;
  const std::string &tier = options->tier, &case_dir = options->case_dir, &out_dir = options->out_dir;
  try {
    const verification::Thresholds thresholds(case_dir + "/thresholds.yaml");
    auto threshold = [&](const char* key) { return thresholds.value(key); };
    auto range = [&](const char* key) { return thresholds.range(key); };
    std::filesystem::create_directories(out_dir);
    std::filesystem::remove(out_dir + "/interface_bimaterial.csv");

    std::map<std::string, VariantResult> results;
    std::vector<std::string> order;
    for (const Variant& v : kVariants) {
      if (tier == "quick" && !v.quick) continue;
      VariantResult r = run_variant(v, case_dir, out_dir, tier);
      const Pattern& p = r.pattern;
      std::fprintf(stderr,
                   "propagation %-13s blocks %4d  %s  t %4.1f s  wetted %3d  x %+6.2f..%+6.2f  y %+6.2f..%+6.2f  "
                   "mass %.1e  %.1f s%s%s\n",
                   v.name.c_str(), r.blocks, r.completed ? "completed    " : "NOT COMPLETED", r.run.time_s, p.wetted,
                   -p.left, p.right, -p.down, p.up, r.max_over(&Sample::mass_balance_error), r.run.wall_seconds,
                   r.message.empty() ? "" : "\n    ", r.message.c_str());
      order.push_back(v.name);
      results.emplace(v.name, std::move(r));
    }
    if (results.count("bimaterial")) {
      std::string text = "x_m,v_upper_m,v_lower_m\n";
      for (const auto& row : results.at("bimaterial").faces.rows)
        text += number(row[0]) + "," + number(row[1]) + "," + number(row[2]) + "\n";
      io::write_file_atomically(out_dir + "/interface_bimaterial.csv", text);
    }

    // ---- checks
    std::vector<Check> checks;
    auto add = [&](const VariantResult& r, const std::string& what, double value, nlohmann::json limit,
                   const std::string& comparison, bool gating, const std::string& note) {
      // A pattern check is about the state after 30 s: a run that stopped earlier has no
      // value (the check fails); what it had reached is kept in the note.
      checks.push_back({r.variant.label + ": " + what, r.completed ? value : kNaN, std::move(limit), comparison,
                        "pass",
                        r.completed ? note
                                    : note + "; run did not complete: at its last committed step (t = " +
                                          number(r.run.time_s) + " s) the value was " + number(value),
                        gating});
    };
    auto count = [](int n) { return n < 0 ? kNaN : double(n); };
    const VariantResult* free_s0 = results.count("free_s0") ? &results.at("free_s0") : nullptr;
    const double free_half_length =
        free_s0 && free_s0->completed ? 0.5 * free_s0->pattern.x_extent() : kNaN;  // case (a), dsigma = 0

    for (const std::string& name : order) {
      const VariantResult& r = results.at(name);
      const Pattern& p = r.pattern;
      checks.push_back({r.variant.label + ": run completed (30 s)", r.completed ? 1.0 : 0.0, 1.0, "==", "pass",
                        r.completed ? "" : r.message, true});
      checks.push_back({r.variant.label + ": max over steps of the relative mass balance error",
                        r.max_over(&Sample::mass_balance_error), threshold("mass_balance_error"), "<=", "pass",
                        !r.history_ok ? r.message : "history.csv column mass_balance_error, every step", true});
      if (!r.built) continue;
      if (name == "free_s0") {
        add(r, "fluid-filled joints off the line y = 0", p.off_y0, threshold("straight_off_line_joints"), "==", true,
            "seed: the fracture proceeded straight outward from the tips (Fig. 3.13 A)");
        add(r, "fluid-filled joints without a fluid-filled mirror image about x = 0", count(p.unmatched_mirror_x),
            threshold("symmetry_unmatched_joints"), "==", true, "symmetric problem and mesh");
        add(r, "half-length (x-extent / 2 of the fluid-filled joints) [m]", 0.5 * p.x_extent(),
            range("seed_half_length_free_m"), "in", false, "seed 3.4: 12 m after 30 s; reported, not gating");
      } else if (name == "free_s5") {
        add(r, "y-extent of the fluid-filled joints [m]", p.y_extent(), threshold("free_s5_min_y_extent_m"), ">=",
            true, "seed: growth turns perpendicular to the minimum compressive stress (x), i.e. along y");
        add(r, "y-extent minus the new growth in x, y_ext - (x_ext - 4 m) [m]", p.y_extent() - (p.x_extent() - 4.0),
            threshold("free_s5_y_minus_new_x_m"), ">", true,
            "seed: after 6 s the fractures had completely realigned (Fig. 3.13 B)");
        add(r, "fluid-filled joints without a mirror image (x = 0, y = 0)",
            count(p.unmatched_mirror_x) + count(p.unmatched_mirror_y), threshold("symmetry_unmatched_joints"), "==",
            false, "symmetric problem; reported, not gating");
      } else if (name == "cross_s0") {
        add(r, "shortest of the four branches [m]", std::min({p.right, p.left, p.up, p.down}),
            threshold("cross_s0_min_branch_m"), ">", true, "seed: four branches grew from the cross (Fig. 3.14 A)");
        add(r, "fluid-filled joints on neither axis", p.off_axes, threshold("straight_off_line_joints"), "==", true,
            "seed: branches proceeded straight outward");
        add(r, "fluid-filled joints without an image (mirror x, mirror y, x<->y swap)",
            count(p.unmatched_mirror_x) + count(p.unmatched_mirror_y) + count(p.unmatched_swap),
            threshold("symmetry_unmatched_joints"), "==", true, "seed: proceeded symmetrically in four directions");
        add(r, "longest branch / half-length of case (a) dsigma = 0",
            std::max({p.right, p.left, p.up, p.down}) / free_half_length, threshold("cross_s0_branch_ratio"), "<",
            true, "seed: 8 m against 12 m (each branch carries half the fluid of a wing of case a)");
        add(r, "mean branch length [m]", 0.25 * (p.right + p.left + p.up + p.down), range("seed_branch_cross_m"),
            "in", false, "seed 3.4: 8 m; reported, not gating");
      } else if (name == "cross_s5") {
        add(r, "largest |x| of a fluid-filled joint end [m]", std::max(p.right, p.left),
            threshold("cross_s5_max_abs_x_m"), "<=", true,
            "seed: the horizontal fractures did not propagate beyond the initially open 2 m (Fig. 3.14 B)");
        add(r, "shorter vertical branch [m]", std::min(p.up, p.down), threshold("cross_s5_min_vertical_branch_m"), ">=",
            true, "seed: propagation only in the vertical direction");
      } else if (name == "diagonal_s0") {
        add(r, "smallest fluid-filled diagonal length in a quadrant [m]",
            *std::min_element(p.quadrant_length.begin(), p.quadrant_length.end()),
            threshold("diagonal_s0_min_quadrant_length_m"), ">=", true,
            "seed: four diagonal branches, each continued for the whole run (Fig. 3.15 A)");
        add(r, "fluid-filled joints without an image (mirror x, mirror y)",
            count(p.unmatched_mirror_x) + count(p.unmatched_mirror_y), threshold("symmetry_unmatched_joints"), "==",
            true, "seed: diverged symmetrically");
      } else if (name == "diagonal_s5") {
        add(r, "y-extent / x-extent of the fluid-filled joints", p.y_extent() / p.x_extent(),
            threshold("diagonal_s5_min_y_over_x"), ">", true,
            "seed: zigzag, but the overall trend perpendicular to the minimum compressive stress (Fig. 3.15 B)");
      } else if (name == "leakoff_s0") {
        add(r, "half-length / half-length of case (a) dsigma = 0", 0.5 * p.x_extent() / free_half_length,
            threshold("leakoff_half_length_ratio"), "<", true, "seed: 10 m with leak-off against 12 m without");
        add(r, "leaked mass at the end [kg]", r.leaked_mass, threshold("leakoff_min_leaked_kg"), ">", true,
            "C_L = 2e-5 m/s^0.5 on every wetted joint");
        add(r, "max over steps |initial + injected - stored - leaked| / (initial + injected)",
            r.max_over(&Sample::ledger), threshold("mass_balance_error"), "<=", true,
            "ledger recomputed from the mass columns of history.csv (seed Fig. 3.17)");
        add(r, "half-length [m]", 0.5 * p.x_extent(), range("seed_half_length_leakoff_m"), "in", false,
            "seed 3.4: 10 m; reported, not gating");
      } else if (name == "weak_diagonal") {
        add(r, "fluid-filled length of -45 deg joints minus that of +45 deg joints [m]",
            p.length_minus45 - p.length_plus45, threshold("weak_diagonal_min_excess_m"), ">", true,
            "seed: growth continued only down the weaker (-45 deg) joints (Fig. 3.19)");
      } else if (name == "delaunay") {
        add(r, "x-extent of the fluid-filled joints [m]", p.x_extent(), threshold("min_x_extent_m"), ">", true,
            "the fracture propagated beyond the initial 4 m (seed: 14.0 m left, 9.1 m right)");
        add(r, "y-extent / x-extent of the fluid-filled joints", p.y_extent() / p.x_extent(),
            threshold("delaunay_max_y_over_x"), "<=", true, "seed: did not deviate too far from the horizontal");
        add(r, "shorter wing (min of left, right extent) [m]", std::min(p.left, p.right),
            threshold("delaunay_min_shorter_wing_m"), ">", false,
            "seed: both wings grew, 14.0 m left and 9.1 m right; reported, not gating (asymmetry allowed)");
        add(r, "fluid-filled joints outside the inner domain", p.outside_inner, threshold("straight_off_line_joints"),
            "==", true, "joints.breakable_region: inner keeps the outer domain intact");
      } else if (name == "free_s5_dt05" || name == "free_s5_dt2") {
        const VariantResult* reference = results.count("free_s5") ? &results.at("free_s5") : nullptr;
        const Pattern* q = reference && reference->completed ? &reference->pattern : nullptr;
        const double difference =
            q ? std::max({std::abs(p.left - q->left), std::abs(p.right - q->right), std::abs(p.up - q->up),
                          std::abs(p.down - q->down)})
              : kNaN;
        add(r, "largest difference of the four extents from the dt = 1 s run [m]", difference,
            threshold("time_step_max_extent_difference_m"), "<=", true,
            "beyond the seed: the pattern must not depend on the time step");
      } else if (name == "bimaterial") {
        add(r, "fluid-filled joints off the interface y = 0", p.off_y0, threshold("straight_off_line_joints"), "==",
            true, "seed: the fracture propagated along the interface (Fig. 3.22)");
        add(r, "x-extent of the fluid-filled joints [m]", p.x_extent(), threshold("min_x_extent_m"), ">", true,
            "the fracture propagated beyond the initial 4 m along the interface");
        add(r, "mean |v| lower (5 GPa) faces / mean |v| upper (25 GPa) faces", r.faces.mean_abs_v_lower /
            r.faces.mean_abs_v_upper, threshold("bimaterial_min_opening_ratio"), ">", true,
            "seed: the fracture opened more on the side of the smaller modulus (Fig. 3.23)");
      }
    }

    // ---- result.json
    nlohmann::json result;
    result["case"] = "propagation";
    result["title"] = "Fracture propagation in symmetric and asymmetric media";
    result["seed_section"] = "3.4, 3.5";
    result["tier"] = tier;
    const bool gating_match = verification::record_checks(checks, result);
    const bool all_match = result["status"] == "pass";
    nlohmann::json figures = nlohmann::json::array();
    for (const std::string& name : order) {
      const VariantResult& r = results.at(name);
      const Pattern& p = r.pattern;
      auto& m = result["metrics"][name];
      m["label"] = r.variant.label;
      m["seed"] = r.variant.seed;
      m["case_file"] = r.variant.case_file;
      m["blocks"] = r.blocks;
      m["joints"] = r.joints;
      m["completed"] = r.completed;
      if (!r.message.empty()) m["message"] = r.message;
      m["time_reached_s"] = r.run.time_s;
      m["steps"] = r.run.steps;
      m["wall_s"] = r.run.wall_seconds;
      if (!r.built) continue;
      m["max_mass_balance_error"] = finite_or_null(r.max_over(&Sample::mass_balance_error));
      m["max_ledger_error"] = finite_or_null(r.max_over(&Sample::ledger));
      m["step_cuts_total"] = finite_or_null(r.sum_over(&Sample::step_cuts));
      m["flow_newton_iterations_total"] = finite_or_null(r.sum_over(&Sample::newton));
      m["max_step_wall_s"] = finite_or_null(r.max_over(&Sample::step_wall_s));
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
      if (r.variant.structured)
        m["unmatched"] = {{"mirror_x", p.unmatched_mirror_x}, {"mirror_y", p.unmatched_mirror_y},
                          {"swap_xy", p.unmatched_swap}};
      m["leaked_kg"] = r.leaked_mass;
      m["initial_mass_kg"] = r.initial_mass;
      if (!r.samples.empty()) {
        const Sample& s = r.samples.back();
        m["at_end"] = {{"time_s", s.time_s},
                       {"injection_pressure_Pa", s.pressure},
                       {"injection_aperture_m", s.aperture},
                       {"open_extent_m", {s.xmin, s.xmax, s.ymin, s.ymax}},
                       {"injected_kg", s.injected},
                       {"stored_kg", s.stored},
                       {"leaked_kg", s.leaked}};
      }
      if (name == "bimaterial")
        m["interface"] = {{"wetted_joints", r.faces.joints},
                          {"mean_abs_v_upper_m", finite_or_null(r.faces.mean_abs_v_upper)},
                          {"mean_abs_v_lower_m", finite_or_null(r.faces.mean_abs_v_lower)},
                          {"mean_v_upper_m", finite_or_null(r.faces.mean_v_upper)},
                          {"mean_v_lower_m", finite_or_null(r.faces.mean_v_lower)}};
    }
    if (tier == "quick") {
      figures.push_back("propagation_quick.png");
    } else {
      for (const char* f : {"propagation_free.png", "propagation_cross.png", "propagation_diagonal.png",
                            "propagation_leakoff.png", "propagation_leakoff_mass.png", "propagation_weak_diagonal.png",
                            "propagation_delaunay.png", "propagation_bimaterial.png",
                            "propagation_bimaterial_faces.png", "propagation_time_step.png"})
        figures.push_back(f);
    }
    result["figures"] = figures;
    result["notes"] =
        "Seed 3.4-3.5 patterns turned into numbers. Common setup: 40 m inner domain in a 48 m outer domain (E/25, "
        "nu = 0) with fixed corners, 2 m cells split into four triangles (case f: Delaunay, 1.5 m^2), Table 3.1 "
        "rock and fluid, T0 = 1 MPa, Q0 = 1 kg/s at the origin, the two joints either side of it initially open "
        "and fluid-filled, ALM k = 100 E, dt = 1 s for 30 s, the default numerics for every case (nothing tuned). "
        "The far-field stress (5 MPa, or 5 MPa in x and 10 MPa in y for dsigma = 5 MPa) is in situ: the rock "
        "starts stressed and in equilibrium. Only inner-domain joints may break (all joints unbreakable, the "
        "inner grid lines / diagonals listed as breakable line features), except on the Delaunay mesh. "
        "'Fluid-filled' = wetted by the flow network at the end of the run; extents are measured from the "
        "injection point on the initial mesh coordinates. Gating checks are the seed's unambiguous statements; "
        "comparisons with the seed's quoted lengths are reported, not gating.";
    io::write_file_atomically(out_dir + "/result.json", result.dump(2) + "\n");
    std::fprintf(stderr, "propagation: %s (gating checks %s)\n",
                 all_match ? "all checks as expected" : "some checks missed", gating_match ? "pass" : "FAIL");
    return gating_match ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "verify_propagation: %s\n", e.what());
    return 2;
  }
}
