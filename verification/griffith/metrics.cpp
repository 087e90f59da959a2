// Metrics of the Griffith case (seed 3.1): the opening at every crack node against
// eq. 3.1. Variants, thresholds and checks are in study.yaml; the harness runs them.
// Writes profile_<variant>.csv (x, w, w_exact) for plot.py.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "analytical/griffith.hpp"
#include "harness.hpp"
#include "mesh/mesh.hpp"
#include "simulation/snapshots.hpp"

namespace hfdda::verification {
namespace {

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

std::string profile_csv(const Profile& p) {
  std::string text = "x_m,w_m,w_exact_m\n";
  char line[128];
  for (std::size_t i = 0; i < p.x.size(); ++i) {
    std::snprintf(line, sizeof line, "%.10g,%.10g,%.10g\n", p.x[i], p.w[i], p.w_exact[i]);
    text += line;
  }
  return text;
}

Metrics variant_metrics(const VariantRun& r) {
  if (!r.model) throw std::runtime_error("variant '" + r.variant->name + "': " + r.message);
  const Profile p = crack_profile(*r.model);
  Metrics m;
  m.numbers["max_error"] = p.max_error();
  m.numbers["centre_error"] = p.centre_error();
  m.numbers["vertex_vertex_activations"] = r.run.totals.vertex_vertex_activations;
  m.numbers["exact_peak_width_m"] = p.peak_exact;
  m.json["blocks"] = r.model->system->n_blocks();
  m.json["max_error_over_peak"] = p.max_error();
  m.json["centre_error_over_peak"] = p.centre_error();
  m.files["profile_" + r.variant->name + ".csv"] = profile_csv(p);
  char line[160];
  std::snprintf(line, sizeof line, "blocks %6d  max error %.4f  centre %+.4f  VV %d", r.model->system->n_blocks(),
                p.max_error(), p.centre_error(), r.run.totals.vertex_vertex_activations);
  m.summary = line;
  return m;
}

void study_metrics(StudyOutcome& s) {
  if (s.variants.empty()) return;
  s.metrics.json["exact_peak_width_m"] = s.variants.front().metrics.numbers.at("exact_peak_width_m");
  const VariantOutcome* coarse = s.find("domain400_tri4_alm");
  const VariantOutcome* fine = s.find("domain400_h05_tri4_alm");
  if (coarse && fine)
    s.metrics.numbers["error_ratio_h05_over_h1"] =
        fine->metrics.numbers.at("max_error") / coarse->metrics.numbers.at("max_error");
}

}  // namespace

CaseDefinition case_definition() { return {nullptr, variant_metrics, study_metrics}; }

}  // namespace hfdda::verification
