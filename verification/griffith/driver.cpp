// Verification driver: Griffith crack under constant pressure (seed 3.1).
//
//   verify_griffith --tier quick|full --case-dir DIR --out RESULT_DIR
//
// Runs the case variants through the library's public API, compares the opening at
// every crack node with eq. 3.1, writes RESULT_DIR/result.json (schema in
// verification/README.md), one profile CSV per variant and the run directories.
// Exit code: 0 when every gating check matches its expectation, 1 otherwise.

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "analytical/griffith.hpp"
#include "io/case_config.hpp"
#include "io/output.hpp"
#include "simulation/model.hpp"
#include "simulation/run.hpp"
#include "simulation/snapshots.hpp"

#include "driver_support.hpp"

namespace {

using hfdda::verification::Check;

using namespace hfdda;

struct Variant {
  std::string name;       // also the run directory and profile file name
  std::string case_file;  // in the case directory
  std::string label;      // for the report
  bool quick;             // part of the quick (CI) tier
};

const std::vector<Variant> kVariants{
    {"tri4_alm", "base.yaml", "triangles (4 per cell), ALM", true},
    {"tri4_penalty", "tri4_penalty.yaml", "triangles (4 per cell), penalty", false},
    {"tri2_alm", "tri2_alm.yaml", "triangles (2 per cell), ALM", false},
    {"tri2_penalty", "tri2_penalty.yaml", "triangles (2 per cell), penalty", false},
    {"quad_alm", "quad_alm.yaml", "quadrilaterals, ALM", true},
    {"quad_penalty", "quad_penalty.yaml", "quadrilaterals, penalty", false},
    {"domain200_tri4_alm", "domain200.yaml", "400 m domain, 1 m cells, ALM", false},
    {"domain400_tri4_alm", "domain400.yaml", "800 m domain, 1 m cells, ALM", false},
    {"domain400_h05_tri4_alm", "domain400_h05.yaml", "800 m domain, 0.5 m cells, ALM", true},
};

struct Profile {
  std::vector<double> x, w, w_exact;
  double peak_exact = 0.0;
  double max_error() const {
    double e = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) e = std::max(e, std::abs(w[i] - w_exact[i]));
    return e / peak_exact;
  }
  double centre_error() const {
    const auto it = std::min_element(x.begin(), x.end(), [](double a, double b) { return std::abs(a) < std::abs(b); });
    const std::size_t i = it - x.begin();
    return (w[i] - w_exact[i]) / peak_exact;
  }
};

struct VariantResult {
  Variant variant;
  Profile profile;
  simulation::RunResult run;
  int blocks = 0;
};

/// Opening at each node of the (first) fracture against eq. 3.1.
Profile crack_profile(const simulation::Model& model) {
  const io::CaseConfig& c = model.config;
  const io::FractureConfig& crack = c.fractures.at(0);
  const dda::BlockSystem& system = *model.system;
  const Vec2 centre = 0.5 * (crack.from + crack.to);
  const Vec2 along = (crack.to - crack.from).normalized();
  const double half_length = 0.5 * (crack.to - crack.from).norm();
  const double net_pressure = crack.pressure_Pa.value_or(0.0) - (-c.far_field.syy_Pa);
  const auto& rock = c.materials.at(0);
  const auto joints = mesh::joints_on_segment(system.mesh(), crack.from, crack.to, 1e-9 * half_length);
  Profile p;
  std::vector<std::pair<double, double>> nodes;
  for (const auto& [point, aperture] : simulation::apertures_at_points(system, joints))
    nodes.emplace_back((system.mesh().points[point] - centre).dot(along), aperture);
  std::sort(nodes.begin(), nodes.end());
  for (const auto& [x, w] : nodes) {
    p.x.push_back(x);
    p.w.push_back(w);
    p.w_exact.push_back(
        analytical::griffith_width(x, half_length, net_pressure, rock.youngs_modulus_Pa, rock.poissons_ratio));
  }
  p.peak_exact = analytical::griffith_width(0.0, half_length, net_pressure, rock.youngs_modulus_Pa, rock.poissons_ratio);
  return p;
}

void write_profile(const std::string& path, const Profile& p) {
  std::string text = "x_m,w_m,w_exact_m\n";
  char line[128];
  for (std::size_t i = 0; i < p.x.size(); ++i) {
    std::snprintf(line, sizeof line, "%.10g,%.10g,%.10g\n", p.x[i], p.w[i], p.w_exact[i]);
    text += line;
  }
  io::write_file_atomically(path, text);
}


}  // namespace

int main(int argc, char** argv) {
  const auto options = verification::parse_driver_options(argc, argv, "verify_griffith");
  if (!options) return 2;
  const std::string &tier = options->tier, &case_dir = options->case_dir, &out_dir = options->out_dir;
  try {
    const verification::Thresholds thresholds(case_dir + "/thresholds.yaml");
    auto threshold = [&](const char* key) { return thresholds.value(key); };
    std::filesystem::create_directories(out_dir);

    std::vector<VariantResult> results;
    for (const Variant& v : kVariants) {
      if (tier == "quick" && !v.quick) continue;
      const io::CaseConfig config = io::load_case_file(case_dir + "/" + v.case_file);
      simulation::Model model = simulation::build_model(config);
      VariantResult r{v, {}, {}, model.system->n_blocks()};
      r.run = simulation::run(model, {out_dir + "/runs/" + v.name, true, tier == "full" && v.name == "tri4_alm"});
      r.profile = crack_profile(model);
      write_profile(out_dir + "/profile_" + v.name + ".csv", r.profile);
      std::fprintf(stderr, "griffith %-24s blocks %6d  max error %.4f  centre %+.4f  VV %d  %.2f s\n", v.name.c_str(),
                   r.blocks, r.profile.max_error(), r.profile.centre_error(), r.run.totals.vertex_vertex_activations,
                   r.run.wall_seconds);
      results.push_back(std::move(r));
    }
    auto find = [&](const std::string& name) -> const VariantResult* {
      for (const auto& r : results)
        if (r.variant.name == name) return &r;
      return nullptr;
    };

    std::vector<Check> checks;
    if (const auto* r = find("tri4_alm"))
      checks.push_back({"seed geometry, triangles, ALM: max|w - w_exact| / w_peak", r->profile.max_error(),
                        threshold("seed_geometry_max_error"), "<=", "pass",
                        "issue target; not gating (finite 100 m domain, see notes)", false});
    if (const auto* r = find("domain400_h05_tri4_alm"))
      checks.push_back({"800 m domain, 0.5 m cells, triangles, ALM: max|w - w_exact| / w_peak",
                        r->profile.max_error(), threshold("converged_max_error"), "<=", "pass",
                        "truncation removed, mesh refined", true});
    for (const char* name : {"quad_alm", "quad_penalty"})
      if (const auto* r = find(name))
        checks.push_back({std::string("seed geometry, ") + r->variant.label + ": max|w - w_exact| / w_peak",
                          r->profile.max_error(), threshold("quadrilateral_max_error"), "<=", "fail",
                          "seed 3.1: quadrilaterals do not give the Griffith profile", true});
    for (const auto& r : results)
      if (r.variant.name.find("alm") != std::string::npos && r.variant.name.find("quad") == std::string::npos)
        checks.push_back({r.variant.label + ": vertex-vertex contacts activated",
                          double(r.run.totals.vertex_vertex_activations), threshold("alm_vertex_vertex_activations"),
                          "<=", "pass", "seed 3.1: none with the ALM", true});
    for (const char* name : {"tri4_penalty", "tri2_penalty"})
      if (const auto* r = find(name))
        checks.push_back({r->variant.label + ": vertex-vertex contacts activated",
                          double(r->run.totals.vertex_vertex_activations), 0.0, ">", "pass",
                          "seed 3.1: many with the penalty method", true});
    const auto* coarse = find("domain400_tri4_alm");
    const auto* fine = find("domain400_h05_tri4_alm");
    if (coarse && fine)
      checks.push_back({"800 m domain: error ratio h = 0.5 m / h = 1 m", fine->profile.max_error() / coarse->profile.max_error(),
                        1.0, "<=", "pass", "the mesh error must shrink with refinement", true});

    nlohmann::json result;
    result["case"] = "griffith";
    result["title"] = "Griffith crack under constant pressure";
    result["seed_section"] = "3.1";
    result["tier"] = tier;
    const bool gating_match = verification::record_checks(checks, result);
    const bool all_match = result["status"] == "pass";
    for (const auto& r : results) {
      auto& m = result["metrics"][r.variant.name];
      m["label"] = r.variant.label;
      m["blocks"] = r.blocks;
      m["max_error_over_peak"] = r.profile.max_error();
      m["centre_error_over_peak"] = r.profile.centre_error();
      m["vertex_vertex_activations"] = r.run.totals.vertex_vertex_activations;
      m["steps"] = r.run.steps;
      m["factorizations"] = r.run.totals.factorizations;
      m["wall_s"] = r.run.wall_seconds;
      m["completed"] = r.run.completed;
    }
    result["metrics"]["exact_peak_width_m"] = results.front().profile.peak_exact;
    result["figures"] = tier == "full" ? nlohmann::json{"griffith_profiles.png", "griffith_convergence.png"}
                                       : nlohmann::json{"griffith_profiles.png"};
    result["notes"] =
        "Opening at the crack nodes (mean face separation) against eq. 3.1 for an infinite plane. "
        "The seed's 100 m domain with free sides widens the crack (about +4.6 % at the centre, from the domain "
        "study), while 1 m cells under-resolve the tip (about -4 % at the node next to the tip on the 800 m domain, "
        "halving at 0.5 m). Quadrilateral blocks lock, as the seed reports. Gating checks (CI) are marked; the "
        "issue's 3 % target on the seed geometry is reported whatever its outcome.";
    io::write_file_atomically(out_dir + "/result.json", result.dump(2) + "\n");
    std::fprintf(stderr, "griffith: %s (gating checks %s)\n", all_match ? "all checks as expected" : "some checks missed",
                 gating_match ? "pass" : "FAIL");
    return gating_match ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "verify_griffith: %s\n", e.what());
    return 2;
  }
}
