// Checkpoint state of the flow network. Besides the committed state, the last trial's
// nodes and fill states (and the rest of its TrialNetwork) are stored: the next step
// starts its Newton iterations from them (warm start), so leaving them out would change
// the iterates, if not the result.

#include <algorithm>
#include <cstdint>

#include "core/binary_io.hpp"
#include "fluid/flow_network.hpp"

namespace hfdda::fluid {

void FlowNetwork::save_state(BinaryWriter& out) const {
  out.put<std::int64_t>(n_points());
  out.put<std::int64_t>(n_fractures());
  out.put<std::uint64_t>(injections_.size());
  for (double v : {time_s_, injected_kg_, leaked_kg_, vented_kg_, initial_mass_, trial_.dt_s, trial_.homotopy})
    out.put(v);
  out.put_vector(wetted_);
  out.put_vector(arrival_time_);
  out.put_vector(aperture_);
  out.put_vector(point_pressure_);
  out.put_vector(point_mass_);
  out.put_vector(point_state_);
  out.put_vector(reached_);
  out.put_vector(guess_state_);
  out.put_vector(trial_wetted_);
  out.put_vector(trial_fractures_);
  out.put_vector(trial_nodes_);
  out.put_vector(node_of_point_);
  out.put_vector(trial_.node_a);
  out.put_vector(trial_.node_b);
  for (const Eigen::VectorXd* v : {&trial_.old_mass_kg, &trial_.injected_kg, &trial_.leak_volume_m3, &trial_.floor_m,
                                   &unknowns_, &pressure_, &aperture_trial_, &mass_new_, &leak_mass_,
                                   &vent_mass_, &trial_.fill_scale_Pa})
    out.put_matrix(*v);
}

void FlowNetwork::restore_state(BinaryReader& in) {
  in.expect<std::int64_t>(n_points(), "flow network points");
  in.expect<std::int64_t>(n_fractures(), "flow network fractures");
  in.expect<std::uint64_t>(injections_.size(), "injections");
  for (double* v : {&time_s_, &injected_kg_, &leaked_kg_, &vented_kg_, &initial_mass_, &trial_.dt_s, &trial_.homotopy})
    in.get(*v);
  in.get_vector(wetted_);
  in.get_vector(arrival_time_);
  in.get_vector(aperture_);
  in.get_vector(point_pressure_);
  in.get_vector(point_mass_);
  in.get_vector(point_state_);
  in.get_vector(reached_);
  in.get_vector(guess_state_);
  in.get_vector(trial_wetted_);
  in.get_vector(trial_fractures_);
  in.get_vector(trial_nodes_);
  in.get_vector(node_of_point_);
  in.get_vector(trial_.node_a);
  in.get_vector(trial_.node_b);
  for (Eigen::VectorXd* v : {&trial_.old_mass_kg, &trial_.injected_kg, &trial_.leak_volume_m3, &trial_.floor_m,
                             &unknowns_, &pressure_, &aperture_trial_, &mass_new_, &leak_mass_,
                             &vent_mass_, &trial_.fill_scale_Pa})
    in.get_matrix(*v);
  const std::size_t nf = fractures_.size(), np = node_of_point_.size();
  if (wetted_.size() != nf || arrival_time_.size() != nf || aperture_.size() != 2 * nf || trial_wetted_.size() != nf ||
      point_pressure_.size() != np || point_mass_.size() != np || point_state_.size() != np || reached_.size() != np ||
      guess_state_.size() != np || np != static_cast<std::size_t>(n_points()) ||
      trial_.floor_m.size() != 2 * static_cast<Eigen::Index>(trial_fractures_.size()) ||
      std::any_of(trial_fractures_.begin(), trial_fractures_.end(), [&](int f) { return f < 0 || f >= n_fractures(); }))
    throw std::runtime_error("checkpoint does not match the model: flow network fields");
  // Not stored: they follow from the fractures, the vents, the trial topology and the floors.
  set_trial_fracture_data();
}

}  // namespace hfdda::fluid
