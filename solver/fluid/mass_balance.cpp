#include "fluid/mass_balance.hpp"

#include <algorithm>
#include <limits>

namespace hfdda::fluid {

namespace {
/// Width of the rounded corner of max(w, floor), relative to the floor.
constexpr double kFloorRounding = 0.01;
}  // namespace

void MassBalance::evaluate(const Eigen::VectorXd& x, const Eigen::VectorXd& base, const ApertureModel& s,
                           Evaluation& out, bool with_jacobian) const {
  evaluate_pressure(x, out);
  evaluate_aperture(base, s, out);
  evaluate_storage(x, out);
  evaluate_flow(out);
  if (!with_jacobian) return;
  evaluate_jacobian(x, out);
}

void MassBalance::evaluate_pressure(const Eigen::VectorXd& x, Evaluation& out) const {
  const int n = network_.n_nodes();
  // The unknown y of a node is its fill state: for y >= 0 the node is full at pressure
  // y and stores rho(y) V (eq. 2.6); for y < 0 it is a zero-pressure node (seed 2.1,
  // Figure 2.2) filled to the fraction 1 + y / P, storing rho(0) V (1 + y / P). The
  // pressure that drives the flow and loads the rock is max(y, 0), its corner rounded
  // within kPressureRounding. P (fill_scale_Pa) only shapes the path Newton takes.
  out.pressure.resize(n);
  out.pressure_slope.resize(n);
  for (int i = 0; i < n; ++i) {
    const double y = x[i];
    if (is_vent(i)) {
      out.pressure[i] = 0.0, out.pressure_slope[i] = 0.0;
    } else if (y >= kPressureRounding) {
      out.pressure[i] = y, out.pressure_slope[i] = 1.0;
    } else if (y <= -kPressureRounding) {
      out.pressure[i] = 0.0, out.pressure_slope[i] = 0.0;
    } else {
      out.pressure[i] = (y + kPressureRounding) * (y + kPressureRounding) / (4.0 * kPressureRounding);
      out.pressure_slope[i] = (y + kPressureRounding) / (2.0 * kPressureRounding);
    }
  }
}

void MassBalance::evaluate_aperture(const Eigen::VectorXd& base, const ApertureModel& s, Evaluation& out) const {
  const int nf = network_.n_fractures();
  const Eigen::VectorXd& floor_m = network_.floor_m;
  // w = max(w_mechanics, floor), its corner rounded by a parabola within 1 % of the
  // floor (C1, exact outside that band) so that Newton sees a smooth mass balance.
  s.apply(out.pressure, out.aperture);
  out.aperture += base + network_.hydraulic_width_m;
  out.slope.resize(2 * nf);
  for (int e = 0; e < 2 * nf; ++e) {
    const double band = kFloorRounding * floor_m[e];
    const double z = out.aperture[e] - floor_m[e];
    if (z >= band) {
      out.slope[e] = 1.0;
    } else if (z <= -band) {
      out.aperture[e] = floor_m[e];
      out.slope[e] = 0.0;
    } else {
      out.aperture[e] = floor_m[e] + (z + band) * (z + band) / (4.0 * band);
      out.slope[e] = (z + band) / (2.0 * band);
    }
  }
}

void MassBalance::evaluate_storage(const Eigen::VectorXd& x, Evaluation& out) const {
  const int n = network_.n_nodes();
  const int nf = network_.n_fractures();
  out.density.resize(n);
  for (int i = 0; i < n; ++i) out.density[i] = fluid_.density(out.pressure[i]);
  out.volume.setZero(n);
  for (int k = 0; k < nf; ++k) {
    const double half = 0.5 * network_.length_m[k];
    out.volume[network_.node_a[k]] += half * out.aperture[2 * k];
    out.volume[network_.node_b[k]] += half * out.aperture[2 * k + 1];
  }
  out.storage.resize(n);
  out.vented.setZero(n);
  out.residual.resize(n);
  for (int i = 0; i < n; ++i) {
    out.storage[i] = fill_density(x[i], i) * out.volume[i] + system_storage_slope(i) * out.pressure[i];
    if (is_vent(i) && x[i] > 0.0) out.vented[i] = fluid_.density(0.0) * out.volume[i] * x[i] / network_.fill_scale_Pa[i];
    out.residual[i] = out.storage[i] - network_.old_mass_kg[i] +
                      network_.homotopy * (wetted_fraction(x[i], i) * out.density[i] * network_.leak_volume_m3[i] -
                                           network_.injected_kg[i]);
  }
}

void MassBalance::evaluate_flow(Evaluation& out) const {
  const int nf = network_.n_fractures();
  out.eta.resize(nf);
  const double mu12 = 12.0 * fluid_.viscosity_Pa_s;
  for (int k = 0; k < nf; ++k) {
    const int a = network_.node_a[k], b = network_.node_b[k];
    const double length = network_.length_m[k];
    const double rho = 0.5 * (out.density[a] + out.density[b]);
    const double w = 0.5 * (out.aperture[2 * k] + out.aperture[2 * k + 1]);
    out.eta[k] = rho * w * w * w / (mu12 * length);  // eq. 2.2
    const double outflow = network_.flow_dt() * out.eta[k] * (out.pressure[a] - out.pressure[b]);
    out.residual[a] += outflow;
    out.residual[b] -= outflow;
  }
}

void MassBalance::evaluate_jacobian(const Eigen::VectorXd& x, Evaluation& out) const {
  const int n = network_.n_nodes();
  const int nf = network_.n_fractures();
  const Eigen::VectorXd& leak_volume = network_.leak_volume_m3;
  out.conductance = fluid_.density_derivative() * out.volume;
  for (int i = 0; i < n; ++i) out.conductance[i] += system_storage_slope(i);
  for (int k = 0; k < nf; ++k) {
    out.conductance[network_.node_a[k]] += network_.flow_dt() * out.eta[k];
    out.conductance[network_.node_b[k]] += network_.flow_dt() * out.eta[k];
  }

  // Derivatives with respect to the pressures p first (local and coupling), then by
  // the chain rule to the unknowns y: the columns of both scale by dp/dy, which for
  // the coupling part is the d of J = A + E S diag(d).
  const double drho = fluid_.density_derivative();
  std::vector<Eigen::Triplet<double>> local, coupling;
  local.reserve(n + 4 * nf);
  coupling.reserve(6 * nf);
  for (int i = 0; i < n; ++i)
    local.emplace_back(i, i, network_.homotopy * drho * wetted_fraction(x[i], i) * leak_volume[i]);
  for (int k = 0; k < nf; ++k) {
    const double half = 0.5 * network_.length_m[k];
    for (int end = 0; end < 2; ++end) {
      const int i = end == 0 ? network_.node_a[k] : network_.node_b[k];
      if (out.slope[2 * k + end] > 0.0)
        coupling.emplace_back(i, 2 * k + end, fill_density(x[i], i) * half * out.slope[2 * k + end]);
    }
  }
  add_flow_jacobian(out, local, coupling);
  out.local.resize(n, n);
  out.local.setFromTriplets(local.begin(), local.end());
  out.coupling.resize(n, 2 * nf);
  out.coupling.setFromTriplets(coupling.begin(), coupling.end());
  out.local = out.local * out.pressure_slope.asDiagonal();
  for (int i = 0; i < n; ++i) {
    double diagonal = fill_density_slope(x[i], i) * out.volume[i] +  // storage
                      system_storage_slope(i) * out.pressure_slope[i];  // and the injection system's
    if (x[i] < 0.0)
      diagonal += network_.homotopy * out.density[i] * leak_volume[i] / network_.fill_scale_Pa[i];  // wetted part
    out.local.coeffRef(i, i) += diagonal;
  }
}

void MassBalance::add_flow_jacobian(const Evaluation& out, std::vector<Eigen::Triplet<double>>& local,
                                    std::vector<Eigen::Triplet<double>>& coupling) const {
  const int nf = network_.n_fractures();
  const double drho = fluid_.density_derivative();
  const double flow_dt = network_.flow_dt();
  for (int k = 0; k < nf; ++k) {
    const int a = network_.node_a[k], b = network_.node_b[k];
    const double rho = 0.5 * (out.density[a] + out.density[b]);
    const double w = 0.5 * (out.aperture[2 * k] + out.aperture[2 * k + 1]);
    const double dp = out.pressure[a] - out.pressure[b];
    const double g = flow_dt * out.eta[k];
    // Outflow dt eta (p_a - p_b) from a to b: eta ~ rho w^3 (eq. 2.2).
    for (int end = 0; end < 2; ++end)
      if (out.slope[2 * k + end] > 0.0) {
        const double d_outflow = flow_dt * dp * 1.5 * out.eta[k] / w * out.slope[2 * k + end];
        coupling.emplace_back(a, 2 * k + end, d_outflow);
        coupling.emplace_back(b, 2 * k + end, -d_outflow);
      }
    const double d_density = flow_dt * dp * 0.5 * drho * out.eta[k] / rho;
    local.emplace_back(a, a, g + d_density);
    local.emplace_back(a, b, -g + d_density);
    local.emplace_back(b, b, g - d_density);
    local.emplace_back(b, a, -g - d_density);
  }
}

double MassBalance::fill_density(double y, int i) const {
  // A vent node's fill fraction 1 + y / P runs on past 1: the excess is vented.
  return y >= 0.0 && !is_vent(i) ? fluid_.density(y) : fluid_.density(0.0) * (1.0 + y / network_.fill_scale_Pa[i]);
}

double MassBalance::fill_density_slope(double y, int i) const {
  return y >= 0.0 && !is_vent(i) ? fluid_.density_derivative() : fluid_.density(0.0) / network_.fill_scale_Pa[i];
}

double MassBalance::wetted_fraction(double y, int i) const {
  // Leak-off leaves through the wetted walls: all of them at a full node, the filled
  // fraction of them at a partly filled one. So a node cannot lose more fluid than it
  // receives: as it empties, its leak-off vanishes with its content.
  return y >= 0.0 ? 1.0 : 1.0 + y / network_.fill_scale_Pa[i];
}

double MassBalance::state_of_unknown(double y, int i) const {
  if (y >= 0.0) return is_vent(i) ? 0.0 : y;  // a vent node that vented is full at zero pressure
  return y / network_.fill_scale_Pa[i];
}

double MassBalance::mass_scale() const {
  return std::max(network_.old_mass_kg.sum() + network_.injected_kg.sum(), 1e-300);
}

double MassBalance::residual_round_off() const {
  const double gross = network_.old_mass_kg.sum() + network_.injected_kg.sum() +
                       fluid_.density(0.0) * network_.leak_volume_m3.sum();
  return 64.0 * std::numeric_limits<double>::epsilon() * gross;
}

}  // namespace hfdda::fluid
