#include "simulation/model_flow.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <memory>
#include <string>

#include "core/errors.hpp"
#include "simulation/stop_conditions.hpp"

namespace hfdda::simulation::detail {

namespace {

/// The mesh point of injection i: the single place of the mesh-point rules of an
/// injection (io/ checks only that it lies in the domain). It must be a mesh point,
/// at the end of a joint of a fluid-filled fracture (`filled_joints_at` > 0).
int injection_point(const mesh::Mesh& m, const io::CaseConfig& c, std::size_t i,
                    const std::vector<int>& filled_joints_at) {
  const auto& inj = c.injections[i];
  const std::string key = "injections[" + std::to_string(i) + "].at";
  const int point = mesh::nearest_point(m, inj.at);
  if ((m.points[point] - inj.at).norm() > 1e-6 * domain_size(c))
    throw InputError(c.file, inj.line, key,
                     "injection point " + format_point(inj.at) + " is not a mesh point (nearest " +
                         format_point(m.points[point]) + "); put it on the end of a fracture joint");
  if (filled_joints_at[point] == 0)
    throw InputError(c.file, inj.line, key,
                     "injection point " + format_point(inj.at) +
                         " must lie on a fracture with `fluid_filled: true` (the fluid needs somewhere to go)");
  return point;
}

}  // namespace

InitialFill build_flow_network(Model& model, const io::CaseConfig& c) {
  const mesh::Mesh& m = model.system->mesh();
  std::vector<fluid::Fracture> fractures;
  fractures.reserve(m.joints.size());
  for (const auto& j : m.joints)
    fractures.push_back(
        {j.point_p, j.point_q, (m.points[j.point_q] - m.points[j.point_p]).norm(), j.properties.hydraulic_width_m});
  fluid::FluidProperties props;
  props.density_kg_m3 = c.fluid->density_kg_m3;
  props.bulk_modulus_Pa = c.fluid->bulk_modulus_Pa;
  props.viscosity_Pa_s = c.fluid->viscosity_Pa_s;
  props.reference_pressure_Pa = c.fluid->reference_pressure_Pa;
  props.leak_off_coefficient_m_sqrt_s = c.fluid->leak_off_coefficient_m_sqrt_s;
  fluid::FlowSettings settings;
  settings.min_width_main_m = c.numerics.min_width_main_m;
  settings.min_width_tip_m = c.numerics.min_width_tip_m;
  settings.max_closing_fraction = c.numerics.max_closing_fraction;
  settings.tolerance = c.numerics.coupling_tolerance;
  settings.max_newton_iterations = c.numerics.max_coupling_iterations;
  settings.inexact_linear_solves = c.numerics.inexact_flow_solves;
  model.flow = std::make_unique<fluid::FlowNetwork>(static_cast<int>(m.points.size()), std::move(fractures), props,
                                                    settings);

  InitialFill fill;
  fill.filled_joints_at.assign(m.points.size(), 0);
  for (std::size_t j = 0; j < m.joints.size(); ++j) {
    const int f = model.fracture_of_joint[j];
    const int written = f < 0 ? -1 : model.fractures[f].config_index;
    if (written < 0 || !c.fractures[written].fluid_filled) continue;
    const io::FractureConfig& fracture = c.fractures[written];
    if (fracture.initial_opening == io::InitialOpening::elastic)
      fill.opened_by_fluid.push_back({static_cast<int>(j), fracture.initial_pressure_Pa});
    else
      model.flow->fill_initially(static_cast<int>(j), fracture.initial_width_m, fracture.initial_pressure_Pa);
    ++fill.filled_joints_at[m.joints[j].point_p];
    ++fill.filled_joints_at[m.joints[j].point_q];
  }
  for (std::size_t i = 0; i < c.injections.size(); ++i) {
    const int point = injection_point(m, c, i, fill.filled_joints_at);
    fluid::Injection injection{point, c.injections[i].mass_rate_kg_s, c.injections[i].start_time_s,
                               c.injections[i].mass_limit_kg.value_or(std::numeric_limits<double>::infinity()),
                               c.injections[i].system_compliance_m2_Pa};
    const bool pressurised_at_start =
        model.flow->pressure(point) > 0.0 ||
        std::any_of(fill.opened_by_fluid.begin(), fill.opened_by_fluid.end(), [&](const auto& opened) {
          return opened.pressure_Pa > 0.0 &&
                 (m.joints[opened.joint].point_p == point || m.joints[opened.joint].point_q == point);
        });
    if (injection.system_compliance_m2_Pa > 0.0 && pressurised_at_start)
      throw ModelError("injection '" + c.injections[i].name + "' (line " + std::to_string(c.injections[i].line) +
                       "): system_compliance needs the fluid at its point to start at zero pressure "
                       "(its fracture has initial_pressure > 0)");
    model.flow->add_injection(injection);
    model.injection_points.push_back(point);
  }
  if (c.fluid->edge == "vented") {
    std::vector<char> vents = inner_boundary_points(m, c);
    for (std::size_t i = 0; i < model.injection_points.size(); ++i)
      if (vents[model.injection_points[i]])
        throw ModelError("injection '" + c.injections[i].name + "' (line " + std::to_string(c.injections[i].line) +
                         ") is on the vented edge (fluid.edge: vented): its fluid would leave at once");
    model.flow->set_vents(std::move(vents));
  }
  for (const auto& probe : c.probes) model.probe_points.push_back(mesh::nearest_point(m, probe.at));
  // The converged contacts' response is formed densely: auto then stays dense.
  const bool dense_only = c.numerics.aperture_response == io::ApertureResponse::converged_contacts;
  coupling::FlowJacobian jacobian = coupling::FlowJacobian::dense;
  if (c.numerics.flow_jacobian == io::FlowJacobianKind::krylov) jacobian = coupling::FlowJacobian::krylov;
  if (c.numerics.flow_jacobian == io::FlowJacobianKind::augmented) jacobian = coupling::FlowJacobian::augmented;
  if (c.numerics.flow_jacobian == io::FlowJacobianKind::automatic && !dense_only)
    jacobian = coupling::FlowJacobian::automatic;
  model.coupling = std::make_unique<coupling::HydroMechanicalCoupling>(*model.flow, jacobian);
  return fill;
}

void open_by_initial_pressure(Model& model, const InitialFill& fill) {
  const std::vector<coupling::PressurisedJoint>& joints = fill.opened_by_fluid;
  const io::CaseConfig& c = model.config;
  int line = 0;
  for (const io::FractureConfig& f : c.fractures)
    if (f.fluid_filled && f.initial_opening == io::InitialOpening::elastic) {
      line = f.line;
      break;
    }
  const std::string where = "fractures with initial_opening: elastic (first at line " + std::to_string(line) + ")";
  if (c.numerics.analysis == io::AnalysisKind::dynamic_analysis)
    throw ModelError(where + ": needs numerics.analysis: static (the step that opens them before t = 0 would "
                     "leave the blocks moving)");
  coupling::InitialOpening opening;
  try {
    opening = coupling::open_by_initial_pressure(*model.system, joints, c.time.dt_s, c.numerics.max_step_cuts,
                                                 fracture_rules(c), c.numerics.min_width_main_m);
  } catch (const ConvergenceError& e) {
    throw ModelError(where + ": the rock did not reach equilibrium with the initial pressure in the step before "
                     "t = 0: " + std::string(e.what()));
  }
  model.initial_opening = InitialOpeningSummary{opening.steps, opening.last_relative_change, opening.settled,
                                                opening.growing};
  if (opening.step.bonds_broken > 0)
    throw ModelError(where + ": the initial pressure breaks " + std::to_string(opening.step.bonds_broken) +
                     " bond(s) before t = 0; lower initial_pressure or start the fracture longer");
  // A closed end holds the minimum width its node will have as a floor (a node joining
  // two or more wetted joints, a tip), so that the closing limit does not squeeze out
  // fluid the closed joint cannot pass on (docs/design_notes.md section 31).
  const mesh::Mesh& m = model.system->mesh();
  for (std::size_t i = 0; i < joints.size(); ++i) {
    std::array<double, 2> width = opening.apertures_m[i];
    const auto& joint = m.joints[joints[i].joint];
    const int points[2] = {joint.point_p, joint.point_q};
    for (int end = 0; end < 2; ++end)
      if (fill.filled_joints_at[points[end]] >= 2) width[end] = std::max(width[end], c.numerics.min_width_main_m);
    model.flow->fill_initially(joints[i].joint, width, joints[i].pressure_Pa);
  }
}

}  // namespace hfdda::simulation::detail
