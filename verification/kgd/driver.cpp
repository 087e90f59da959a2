// Verification driver: KGD viscosity-storage fracture (seed 3.2, Figures 3.4-3.6).
//
//   verify_kgd --tier quick|full --case-dir DIR --out RESULT_DIR
//
// Runs the case variants (mesh size dx, time step dt, background stress sigma0) through
// the library's public API, reads each run's history.csv, and compares the half-length,
// inlet width and inlet net pressure with the zero-toughness, zero-leak-off KGD solution
// (M-vertex, analytical/kgd.hpp) at every step and at the end time. Writes
// RESULT_DIR/result.json (schema in verification/README.md), series_<variant>.csv per
// variant, analytical.csv (the reference curves for the plots) and the run directories.
// A variant whose case cannot be built, whose run stops or throws, or whose history.csv
// lacks a column is reported as such (its checks fail); the driver does not stop.
// Exit code: 0 when every gating check matches its expectation, 1 otherwise, 2 on a
// usage or driver error.

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "analytical/kgd.hpp"
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

struct Variant {
  std::string name;       // run directory and series file name
  std::string case_file;  // in the case directory
  std::string label;      // for the report
  double dx_m;            // joint length along the path (as in the case file)
  bool quick;             // part of the quick (CI) tier
};

// Seed 3.2: dx sweep at dt = 0.5 s for sigma0 = 0 and 5 MPa (Figures 3.4, 3.5); dt sweep at
// dx = 0.5 m, sigma0 = 0 (Figure 3.6). "dx05_s0" is the reference of the gating checks.
const std::vector<Variant> kVariants{
    {"dx4_s0", "dx4.yaml", "dx = 4 m, dt = 0.5 s, sigma0 = 0", 4.0, false},
    {"dx2_s0", "dx2.yaml", "dx = 2 m, dt = 0.5 s, sigma0 = 0", 2.0, true},
    {"dx1_s0", "dx1.yaml", "dx = 1 m, dt = 0.5 s, sigma0 = 0", 1.0, false},
    {"dx05_s0", "base.yaml", "dx = 0.5 m, dt = 0.5 s, sigma0 = 0", 0.5, false},
    {"dx4_s5", "dx4_s5.yaml", "dx = 4 m, dt = 0.5 s, sigma0 = 5 MPa", 4.0, false},
    {"dx2_s5", "dx2_s5.yaml", "dx = 2 m, dt = 0.5 s, sigma0 = 5 MPa", 2.0, false},
    {"dx1_s5", "dx1_s5.yaml", "dx = 1 m, dt = 0.5 s, sigma0 = 5 MPa", 1.0, false},
    {"dx05_s5", "s5.yaml", "dx = 0.5 m, dt = 0.5 s, sigma0 = 5 MPa", 0.5, false},
    {"dt2_s0", "dt2.yaml", "dx = 0.5 m, dt = 2 s, sigma0 = 0", 0.5, false},
    {"dt1_s0", "dt1.yaml", "dx = 0.5 m, dt = 1 s, sigma0 = 0", 0.5, false},
    {"dt025_s0", "dt025.yaml", "dx = 0.5 m, dt = 0.25 s, sigma0 = 0", 0.5, false},
};
const std::string kReference = "dx05_s0";
const std::string kQuick = "dx2_s0";

// Columns of history.csv the coupled solver writes (absolute SI values): the checks need
// these; the optional ones only feed metrics and the series files (NaN when absent).
const std::vector<std::string> kRequiredColumns{"time_s",           "injection_pressure_Pa", "injection_aperture_m",
                                                "open_xmin_m",      "open_xmax_m",           "mass_injected_kg",
                                                "mass_stored_kg",   "mass_leaked_kg",        "mass_balance_error"};
const std::vector<std::string> kOptionalColumns{"flow_newton_iterations", "step_wall_s"};

/// Physical parameters of a variant, read from its case file.
struct Physics {
  double youngs_modulus_Pa = kNaN, poissons_ratio = kNaN, viscosity_Pa_s = kNaN;
  double total_rate_m2_s = kNaN;   ///< Q0 = mass rate / fluid density (per metre of height)
  double mass_rate_kg_s = kNaN;
  double start_time_s = 0.0;
  double sigma0_Pa = kNaN;         ///< background stress, compression positive
  double dt_s = kNaN, end_time_s = kNaN;
  Vec2 injection_point{0, 0};
};

/// One row of the comparison with the M-vertex.
struct Sample {
  double t = kNaN;  // time since injection start
  double time_s = kNaN;
  double half_length = kNaN, width = kNaN, net_pressure = kNaN;
  double half_length_exact = kNaN, width_exact = kNaN, net_pressure_exact = kNaN;
  double mass_balance_error = kNaN, coupling_iterations = kNaN, step_wall_s = kNaN;
  double mass_injected = kNaN, mass_stored = kNaN, mass_leaked = kNaN;
};

double relative_error(double value, double exact) { return (value - exact) / exact; }

struct VariantResult {
  Variant variant;
  Physics physics;
  bool built = false;         ///< case read and model built
  bool completed = false;     ///< run reached its end time
  bool history_ok = false;    ///< history.csv read with every required column
  std::string message;        ///< why something failed
  int blocks = 0, path_joints = 0;
  double path_joint_min_m = kNaN, path_joint_max_m = kNaN;
  simulation::RunResult run;
  std::vector<Sample> samples;

  const Sample* at_end() const {
    if (samples.empty() || !completed) return nullptr;
    const Sample& s = samples.back();
    return std::abs(s.time_s - physics.end_time_s) <= 1e-6 * physics.end_time_s ? &s : nullptr;
  }
  double end_error(double Sample::*value, double Sample::*exact) const {
    const Sample* s = at_end();
    return s ? relative_error(s->*value, s->*exact) : kNaN;
  }
  double max_mass_balance_error() const {
    if (!history_ok || samples.empty()) return kNaN;
    double e = 0.0;
    for (const Sample& s : samples) {
      if (!std::isfinite(s.mass_balance_error)) return kNaN;
      e = std::max(e, std::abs(s.mass_balance_error));
    }
    return e;
  }
  void note(const std::string& text) { message += (message.empty() ? "" : "; ") + text; }
};

Physics physics_of(const io::CaseConfig& c) {
  Physics p;
  if (!c.fluid) throw std::runtime_error("case has no 'fluid' section (no flow network)");
  if (c.injections.size() != 1) throw std::runtime_error("case needs exactly one injection");
  const io::MaterialConfig& rock = c.materials.at(0);
  p.youngs_modulus_Pa = rock.youngs_modulus_Pa;
  p.poissons_ratio = rock.poissons_ratio;
  p.viscosity_Pa_s = c.fluid->viscosity_Pa_s;
  p.mass_rate_kg_s = c.injections[0].mass_rate_kg_s;
  p.total_rate_m2_s = p.mass_rate_kg_s / c.fluid->density_kg_m3;  // Q0, both wings, per metre
  p.start_time_s = c.injections[0].start_time_s;
  p.injection_point = c.injections[0].at;
  if (c.far_field.sxx_Pa != c.far_field.syy_Pa)
    throw std::runtime_error("KGD comparison needs an isotropic background stress (sxx == syy)");
  p.sigma0_Pa = 0.0 - c.far_field.syy_Pa;  // tension positive in the case file (0 - x: no -0)
  p.dt_s = c.time.dt_s;
  p.end_time_s = c.time.end_time_s;
  return p;
}

analytical::KgdViscositySolution exact_at(const Physics& p, double t) {
  return analytical::kgd_viscosity_storage(p.youngs_modulus_Pa, p.poissons_ratio, p.viscosity_Pa_s,
                                           p.total_rate_m2_s, t);
}

/// Reads history.csv into samples compared with the M-vertex; `missing_optional` gets the
/// optional columns it lacks. Throws std::runtime_error naming a missing required column
/// or a malformed row.
std::vector<Sample> read_history(const std::string& path, const Physics& p, std::string& missing_optional) {
  const verification::CsvTable table = verification::CsvTable::read(path, kRequiredColumns);
  missing_optional.clear();
  for (const std::string& c : kOptionalColumns)
    if (!table.has(c)) missing_optional += (missing_optional.empty() ? "" : ", ") + c;
  std::vector<Sample> samples;
  for (std::size_t row = 0; row < table.rows(); ++row) {
    auto value = [&](const std::string& name) { return table.value(row, name); };
    Sample s;
    s.time_s = value("time_s");
    s.t = s.time_s - p.start_time_s;
    if (!(s.t > 0.0)) continue;  // the M-vertex starts at t = 0+
    s.half_length = 0.5 * (value("open_xmax_m") - value("open_xmin_m"));
    s.width = value("injection_aperture_m");
    s.net_pressure = value("injection_pressure_Pa") - p.sigma0_Pa;
    s.mass_balance_error = value("mass_balance_error");
    s.coupling_iterations = value("flow_newton_iterations");
    s.step_wall_s = value("step_wall_s");
    s.mass_injected = value("mass_injected_kg");
    s.mass_stored = value("mass_stored_kg");
    s.mass_leaked = value("mass_leaked_kg");
    const auto exact = exact_at(p, s.t);
    s.half_length_exact = exact.half_length_m;
    s.width_exact = exact.inlet_width_m;
    s.net_pressure_exact = exact.inlet_net_pressure_Pa;
    samples.push_back(s);
  }
  return samples;
}

void write_series(const std::string& path, const std::vector<Sample>& samples) {
  std::string text =
      "time_s,half_length_m,half_length_exact_m,inlet_width_m,inlet_width_exact_m,inlet_net_pressure_Pa,"
      "inlet_net_pressure_exact_Pa,mass_balance_error,coupling_iterations,step_wall_s\n";
  for (const Sample& s : samples) {
    for (double v : {s.time_s, s.half_length, s.half_length_exact, s.width, s.width_exact, s.net_pressure,
                     s.net_pressure_exact, s.mass_balance_error, s.coupling_iterations})
      text += number(v) + ",";
    text += number(s.step_wall_s) + "\n";
  }
  io::write_file_atomically(path, text);
}

/// Reference curves for the plots, from the same function the checks use.
void write_analytical(const std::string& path, const Physics& p) {
  std::string text =
      "time_s,half_length_m,inlet_width_m,inlet_net_pressure_Pa,inlet_width_seed_form_m,"
      "inlet_net_pressure_seed_form_Pa\n";
  const int n = 400;
  const double t_end = p.end_time_s - p.start_time_s;
  for (int i = 1; i <= n; ++i) {
    const double t = t_end * std::pow(double(i) / n, 2.0);  // denser at early times
    const auto e = exact_at(p, t);
    text += number(t + p.start_time_s) + "," + number(e.half_length_m) + "," + number(e.inlet_width_m) + "," +
            number(e.inlet_net_pressure_Pa) + "," + number(e.inlet_width_seed_form_m) + "," +
            number(e.inlet_net_pressure_seed_form_Pa) + "\n";
  }
  io::write_file_atomically(path, text);
}

VariantResult run_variant(const Variant& v, const std::string& case_dir, const std::string& out_dir,
                          const std::string& tier) {
  VariantResult r;
  r.variant = v;
  const std::string run_dir = out_dir + "/runs/" + v.name;
  std::filesystem::remove_all(run_dir);  // never read a previous run's history
  std::filesystem::remove(out_dir + "/series_" + v.name + ".csv");
  try {
    const io::CaseConfig config = io::load_case_file(case_dir + "/" + v.case_file);
    r.physics = physics_of(config);
    simulation::Model model = simulation::build_model(config);
    r.built = true;
    r.blocks = model.system->n_blocks();
    const mesh::Mesh& m = model.system->mesh();
    const auto path = mesh::joints_on_segment(m, Vec2(-24, 0), Vec2(24, 0), 1e-6);
    r.path_joints = static_cast<int>(path.size());
    for (int j : path) {
      const double length = (m.points[m.joints[j].point_q] - m.points[m.joints[j].point_p]).norm();
      r.path_joint_min_m = std::isnan(r.path_joint_min_m) ? length : std::min(r.path_joint_min_m, length);
      r.path_joint_max_m = std::isnan(r.path_joint_max_m) ? length : std::max(r.path_joint_max_m, length);
    }
    const bool vtu = tier == "full" && v.name == kReference;
    r.run = simulation::run(model, {run_dir, true, vtu});
    r.completed = r.run.completed;
    if (!r.completed) r.note("run stopped at t = " + number(r.run.time_s) + " s: " + r.run.message);
  } catch (const std::exception& e) {
    r.note(std::string(r.built ? "run failed: " : "case not built: ") + e.what());
  }
  if (r.built) {
    try {
      std::string missing_optional;
      r.samples = read_history(run_dir + "/history.csv", r.physics, missing_optional);
      r.history_ok = true;
      if (!missing_optional.empty()) r.note("history.csv lacks optional column(s) " + missing_optional);
      write_series(out_dir + "/series_" + v.name + ".csv", r.samples);
    } catch (const std::exception& e) {
      r.note(e.what());
    }
  }
  if (r.completed && r.history_ok && !r.at_end()) r.note("history.csv has no row at the end time");
  return r;
}


}  // namespace

int main(int argc, char** argv) {
  const auto options = verification::parse_driver_options(argc, argv, "verify_kgd");
  if (!options) return 2;
  const std::string &tier = options->tier, &case_dir = options->case_dir, &out_dir = options->out_dir;
  try {
    const verification::Thresholds thresholds(case_dir + "/thresholds.yaml");
    auto threshold = [&](const char* key) { return thresholds.value(key); };
    std::filesystem::create_directories(out_dir);

    std::vector<VariantResult> results;
    for (const Variant& v : kVariants) {
      if (tier == "quick" && !v.quick) continue;
      VariantResult r = run_variant(v, case_dir, out_dir, tier);
      std::fprintf(stderr, "kgd %-9s blocks %5d  path joints %3d  %s  l %+.4f  w0 %+.4f  p0 %+.4f  mass %.2e  %.1f s%s%s\n",
                   v.name.c_str(), r.blocks, r.path_joints, r.completed ? "completed" : "NOT COMPLETED",
                   r.end_error(&Sample::half_length, &Sample::half_length_exact),
                   r.end_error(&Sample::width, &Sample::width_exact),
                   r.end_error(&Sample::net_pressure, &Sample::net_pressure_exact), r.max_mass_balance_error(),
                   r.run.wall_seconds, r.message.empty() ? "" : "\n    ", r.message.c_str());
      results.push_back(std::move(r));
    }
    for (const auto& r : results)
      if (r.built) {
        write_analytical(out_dir + "/analytical.csv", r.physics);
        break;
      }

    // ---- checks
    std::vector<Check> checks;
    for (const auto& r : results) {
      checks.push_back({r.variant.label + ": run completed", r.completed ? 1.0 : 0.0, 1.0, "==", "pass",
                        r.completed ? "" : r.message, true});
      checks.push_back({r.variant.label + ": max over steps of the relative mass balance error",
                        r.max_mass_balance_error(), threshold("mass_balance_error"), "<=", "pass",
                        !r.history_ok        ? r.message
                        : r.samples.empty()  ? "no step completed: nothing to check"
                                             : "history.csv column mass_balance_error, every step",
                        true});
    }
    auto accuracy = [&](const VariantResult& r, bool gating, double half_length_threshold, const std::string& note) {
      const std::string at = r.variant.label + ", t = " + number(r.physics.end_time_s) + " s: ";
      checks.push_back({at + "|l - l_M| / l_M", std::abs(r.end_error(&Sample::half_length, &Sample::half_length_exact)),
                        half_length_threshold, "<=", "pass", note, gating});
      checks.push_back({at + "|w0 - w0_M| / w0_M", std::abs(r.end_error(&Sample::width, &Sample::width_exact)),
                        threshold("reference_inlet_width_error"), "<=", "pass", note, gating && tier == "full"});
      checks.push_back({at + "|p0 - p0_M| / p0_M (net pressure)",
                        std::abs(r.end_error(&Sample::net_pressure, &Sample::net_pressure_exact)),
                        threshold("reference_inlet_net_pressure_error"), "<=", "pass", note, gating && tier == "full"});
    };
    for (const auto& r : results) {
      const std::string& n = r.variant.name;
      if (n == kReference) {
        accuracy(r, tier == "full", threshold("reference_half_length_error"), "target of NOTES section 5");
      } else if (tier == "quick" && n == kQuick) {
        accuracy(r, true, threshold("quick_half_length_error"),
                 "quick tier: l gated at 5 % + one joint (dx / l = 9.7 %); w0, p0 reported against the targets");
      } else {
        std::string note = "reported, not gating";
        if (r.variant.dx_m > 0.5 && r.physics.sigma0_Pa == 0.0)
          note += "; seed Fig. 3.4: l moves in steps of dx, w0 and p0 close to the solution";
        else if (r.variant.dx_m > 0.5)
          note += "; seed Fig. 3.5: with sigma0 = 5 MPa the front lags and w0, p0 overshoot, more so for larger dx";
        else if (r.physics.sigma0_Pa != 0.0)
          note += "; seed Fig. 3.5: good agreement at dx = 0.5 m";
        else if (r.physics.dt_s > 1.0)
          note += "; seed Fig. 3.6: the largest time step (2 s) overshoots l and undershoots w0, p0";
        else
          note += "; seed Fig. 3.6: good agreement";
        accuracy(r, false, threshold("reference_half_length_error"), note);
      }
    }

    // ---- result.json
    nlohmann::json result;
    result["case"] = "kgd";
    result["title"] = "KGD viscosity-storage fracture (M-vertex)";
    result["seed_section"] = "3.2";
    result["tier"] = tier;
    const bool gating_match = verification::record_checks(checks, result);
    const bool all_match = result["status"] == "pass";
    for (const auto& r : results) {
      auto& m = result["metrics"][r.variant.name];
      m["label"] = r.variant.label;
      m["dx_m"] = r.variant.dx_m;
      m["dt_s"] = finite_or_null(r.physics.dt_s);
      m["sigma0_Pa"] = finite_or_null(r.physics.sigma0_Pa);
      m["blocks"] = r.blocks;
      m["path_joints"] = r.path_joints;
      m["path_joint_length_m"] = {finite_or_null(r.path_joint_min_m), finite_or_null(r.path_joint_max_m)};
      m["completed"] = r.completed;
      if (!r.message.empty()) m["message"] = r.message;
      m["time_reached_s"] = r.run.time_s;
      m["steps"] = r.run.steps;
      m["wall_s"] = r.run.wall_seconds;
      m["max_mass_balance_error"] = finite_or_null(r.max_mass_balance_error());
      if (!r.samples.empty()) {
        // Independent of the solver's own mass_balance_error: the ledger from the mass
        // columns, in increments since the first step (the initially fluid-filled joints
        // hold some mass at t = 0), and the injected mass against rate x time.
        const Sample& first = r.samples.front();
        double iterations = 0.0, max_ledger = 0.0, max_rate = 0.0;
        for (const Sample& s : r.samples) {
          iterations += s.coupling_iterations;
          if (s.mass_injected > 0.0) {
            const double residual = (s.mass_injected - first.mass_injected) - (s.mass_stored - first.mass_stored) -
                                    (s.mass_leaked - first.mass_leaked);
            max_ledger = std::max(max_ledger, std::abs(residual) / s.mass_injected);
            max_rate = std::max(max_rate, std::abs(s.mass_injected / (r.physics.mass_rate_kg_s * s.t) - 1.0));
          }
        }
        m["coupling_iterations_total"] = finite_or_null(iterations);
        m["coupling_iterations_per_step"] = finite_or_null(iterations / double(r.samples.size()));
        m["ledger_increments_rel_max"] = max_ledger;
        m["injected_vs_rate_times_time_rel_max"] = max_rate;
      }
      if (const Sample* s = r.at_end()) {
        m["at_end"] = {{"half_length_m", s->half_length},   {"half_length_exact_m", s->half_length_exact},
                       {"inlet_width_m", s->width},         {"inlet_width_exact_m", s->width_exact},
                       {"inlet_net_pressure_Pa", s->net_pressure},
                       {"inlet_net_pressure_exact_Pa", s->net_pressure_exact}};
        m["error_at_end"] = {{"half_length", relative_error(s->half_length, s->half_length_exact)},
                             {"inlet_width", relative_error(s->width, s->width_exact)},
                             {"inlet_net_pressure", relative_error(s->net_pressure, s->net_pressure_exact)}};
      }
    }
    for (const auto& r : results)
      if (r.built) {  // the reference solution at the end time, both published forms
        const auto e = exact_at(r.physics, r.physics.end_time_s - r.physics.start_time_s);
        auto& a = result["metrics"]["m_vertex_at_end"];
        a["Q0_m2_s"] = r.physics.total_rate_m2_s;
        a["half_length_m"] = e.half_length_m;
        a["inlet_width_m"] = e.inlet_width_m;
        a["inlet_net_pressure_Pa"] = e.inlet_net_pressure_Pa;
        a["inlet_width_seed_form_m"] = e.inlet_width_seed_form_m;
        a["inlet_net_pressure_seed_form_Pa"] = e.inlet_net_pressure_seed_form_Pa;
        break;
      }
    result["figures"] = tier == "full"
                            ? nlohmann::json{"kgd_dx_sigma0.png", "kgd_dx_sigma5.png", "kgd_dt.png"}
                            : nlohmann::json{"kgd_quick.png"};
    result["notes"] =
        "Half-length l = (open_xmax - open_xmin) / 2 of the open, fluid-filled fracture; inlet width and net "
        "pressure (fluid pressure minus sigma0) at the injection node; all compared with the zero-toughness, "
        "zero-leak-off KGD solution (M-vertex): l = 0.61524 psi (seed eqs. 3.3-3.4), w0 and p0 from "
        "w0^2 = 2.1 sqrt(mu' Q0 / E') l and w0 p0 = 0.62 sqrt(mu' Q0 E') (NOTES erratum 3; the seed's "
        "eq. 3.3 omits Gamma in w0). The seed's geometry is kept: a 160 m domain with fixed corners and a "
        "fracture up to about 41 m long, so the infinite-plane solution is approached, not matched exactly. "
        "Gating: every run completes and closes its mass ledger to 1e-10 at every step; in the full tier the "
        "reference variant (dx = 0.5 m, dt = 0.5 s, sigma0 = 0) meets the NOTES targets at t = 10 s; in the "
        "quick tier the dx = 2 m run's half-length meets 5 % plus one joint. Every other comparison is reported "
        "against the same targets, not gating.";
    io::write_file_atomically(out_dir + "/result.json", result.dump(2) + "\n");
    std::fprintf(stderr, "kgd: %s (gating checks %s)\n", all_match ? "all checks as expected" : "some checks missed",
                 gating_match ? "pass" : "FAIL");
    return gating_match ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "verify_kgd: %s\n", e.what());
    return 2;
  }
}
