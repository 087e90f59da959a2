#pragma once
// Shared by the coupling tests: a fluid-filled 6 m crack of 1 m joints, initially open,
// in a 40 m square, injected at its centre.

namespace hfdda::coupling_tests {

inline const char* const kFluidFilledCrackCase = R"(
title: "closed fluid-filled crack"
domain:
  outer: {xmin: -20, xmax: 20, ymin: -20, ymax: 20}
  inner: {xmin: -6, xmax: 6, ymin: -4, ymax: 4}
mesh: {type: structured, cell_size: 1.0, outer_growth: 1.4, split: four}
joints: {breakable: false}
fractures:
  - {name: crack, from: [-3, 0], to: [3, 0], initially_open: true, fluid_filled: true}
fluid: {viscosity: 1.0e-3}
injections:
  - {at: [0, 0], mass_rate: 0.5}
fixed_points: [[-20, -20], [20, -20], [20, 20], [-20, 20]]
contact: {method: alm}
numerics: {alm_tolerance: 1.0e-10}
time: {dt: 1.0, end_time: 1.0}
)";

}  // namespace hfdda::coupling_tests
