// The key tables of the solver-control sections of the case file (contact, numerics,
// fracture, time), declared like those of case_tables.cpp: each row names a key, its
// unit, allowed range, seed source and description, and the field kind that reads it.

#include "io/solver_control_tables.hpp"

#include "io/case_fields.hpp"

namespace hfdda::io {

using namespace schema;

const Table<ContactConfig>& contact_table() {
  static const Table<ContactConfig> table{
      "`contact`",
      "Stiffnesses are factors times the largest Young's modulus of the materials.",
      {choice({"method", "", "§2.3: PM or ALM; §3.1: ALM used thereafter",
               "contact enforcement: augmented Lagrangian or penalty"},
              &ContactConfig::method,
              Choices<ContactMethod>{{"alm", ContactMethod::augmented_lagrangian},
                                     {"penalty", ContactMethod::penalty}}),
       number({"normal_stiffness", "-", "Table 3.1: k_n = 100 E; Table 5.1: 30 E",
               "normal spring k_n / max E"},
              &ContactConfig::normal_stiffness_factor,
              interval(kMinStiffnessFactor, false, kMaxStiffnessFactor, false),
              "the seed uses 30 to 100; a spring softer than the rock (below 1) lets blocks overlap "
              "by more than their own elastic strain; beyond 1e6 the stiffness matrix loses all digits"),
       number({"shear_stiffness", "-", "Table 3.1: k_s = 100 E; Table 5.1: 30 E",
               "shear spring k_s / max E"},
              &ContactConfig::shear_stiffness_factor,
              interval(kMinStiffnessFactor, false, kMaxStiffnessFactor, false),
              "as normal_stiffness: below 1 the spring is softer than the rock"),
       number({"vertex_vertex_activation", "m", "§2.3 item v (cited in §3.1)",
               "tolerance for applying vertex-vertex contacts"},
              &ContactConfig::vertex_vertex_activation_m, at_least(0), kWithinDomain),
       number({"fixed_point_stiffness", "-", "§3.3: corners fixed",
               "fixed-point spring / max E"},
              &ContactConfig::fixed_point_stiffness_factor,
              interval(kMinStiffnessFactor, false, kMaxStiffnessFactor, false),
              "below 1 the spring is softer than the rock it holds"),
       boolean({"two_tier", "", "§5.1: ALM on unbroken joints, penalty on sliding and re-closed contacts",
                "with method alm: iterate the multipliers of intact joint contacts only; contacts whose bond "
                "broke (sliding, closed again) and vertex-vertex contacts keep theirs fixed within a step, "
                "as penalty springs"},
               &ContactConfig::two_tier),
       number({"intact_stiffness_ratio", "-", "none (HFDDA): the seed's two tiers share one stiffness",
               "with two_tier: the springs of intact joint contacts, whose multipliers are iterated, are this "
               "many times normal_stiffness and shear_stiffness, which then set the penalty springs of the "
               "other contacts. It sets only how fast the iterations converge, not where: an iterated contact "
               "ends with its gap closed whatever its stiffness. As stiff as the penalty springs beside it, a "
               "contact loses about one seventh of its error per iteration (design notes section 21)"},
              &ContactConfig::intact_stiffness_ratio, interval(1.0, false, 1.0e4, false),
              "1: one stiffness for both tiers, as in the seed; normal_stiffness times this ratio at most 1e6, "
              "beyond which the stiffness matrix loses all digits")}};
  return table;
}

const Table<NumericsConfig>& numerics_table() {
  static const Table<NumericsConfig> table{
      "`numerics`",
      "",
      {choice({"analysis", "", "", "static: velocities reset each step; dynamic: kept"},
              &NumericsConfig::analysis,
              Choices<AnalysisKind>{{"static", AnalysisKind::static_analysis},
                                    {"dynamic", AnalysisKind::dynamic_analysis}}),
       number({"mechanism_inertia_time", "s", "",
               "static analysis: a group of blocks that its closed contacts leave a rigid motion (joined by "
               "joints locked at both ends, touching the rest only through sliding contacts along one line, "
               "or through nothing) takes the inertia term 2 M / tau^2 of this time instead of the step's "
               "2 M / dt^2, which at the minute-long steps of reservoir cases holds nothing; the rest of the "
               "rock mass keeps the step's term (docs/design_notes.md section 25)"},
              &NumericsConfig::mechanism_inertia_time_s, positive_up_to(1e6)),
       boolean({"low_rank_updates", "", "none (HFDDA): the seed factorises K at every open-close iteration",
                "within a time step, the penalty springs that the contact-state changes of an open-close "
                "iteration add or remove (at most 16 at a time and 32 since the step's factorisation of K, and "
                "only when the mechanism holds stay the same) are applied to that factorisation as a low-rank correction "
                "(Woodbury identity) instead of a new factorisation; a correction whose check solve leaves a "
                "residual above 1e-7 is dropped for a new factorisation (docs/design_notes.md section 26; off "
                "by default: the Marcellus case stopped earlier with it)"},
               &NumericsConfig::low_rank_updates),
       number({"alm_tolerance", "-", "§2.3 (ALM)",
               "ALM stop: max abs(k g) <= tolerance * max abs(contact force)"},
              &NumericsConfig::alm_force_tolerance, positive_up_to(1)),
       integer({"max_alm_iterations", "", "§2.3 (ALM)", "ALM iterations per open-close pass"},
               &NumericsConfig::max_alm_iterations, interval(1, false, kMaxIterations, false),
               "the seed needs a few hundred"),
       integer({"max_open_close_iterations", "", "§2.4: outer iterations",
                "open-close iterations per time step"},
               &NumericsConfig::max_open_close_iterations, interval(1, false, kMaxIterations, false)),
       integer({"max_state_flips", "", "§5.1: cycle detection of the open-close states",
                "a contact that changes state more often than this within a step is set to the most open state "
                "it had in the step (open, then sliding, then locked) and held there; such steps are counted "
                "(history cycle_holds, summary steps_with_cycles)"},
               &NumericsConfig::max_state_flips, interval(1, false, kMaxIterations, false)),
       choice({"cycle_resolution", "", "§5.1: most_open",
               "how a contact caught in a cycle is held: most_open (the seed's rule: its most open state "
               "of the step), close_penetrating (the same, except that a joint contact whose faces would "
               "then pass through each other by more than 1e-5 of the joint's length is closed and held "
               "sliding; not in the seed)"},
              &NumericsConfig::cycle_resolution,
              Choices<CycleResolution>{{"most_open", CycleResolution::most_open},
                                       {"close_penetrating", CycleResolution::close_penetrating}}),
       boolean({"relock_in_failure_step", "", "none (HFDDA): DDA locks any sliding contact whose slip reverses (Shi 1988)",
                "a joint contact whose bond broke earlier in the same step and that slides: true, locked again "
                "when its slip since the failure reverses (the rule for every other sliding contact); false, "
                "left sliding until the step ends (it may still open). Within the failing step the slip is "
                "measured from the failure, and a contact re-locked there holds a shear force outside "
                "friction (docs/design_notes.md section 29)"},
               &NumericsConfig::relock_in_failure_step),
       boolean({"friction_at_solution", "", "§2.3, eq. 2.16: false (the normal force at the step's start)",
                "sliding contacts whose springs are held through the step (penalty contacts, two-tier "
                "contacts' unbonded ones): true, friction acts with the normal force of the contact iterate, "
                "iterated to 0.1 % (at most 30 iterates; accelerated once the plain iteration stops contracting, "
                "as in a wedge sharper than the friction angle), and a contact re-locks when its slip in the step "
                "reverses, where it was at the step's start; false, friction acts with the normal force at the "
                "step's start and a contact re-locks once its slip since it last locked reverses. True removes "
                "the windup of sliding wedges under a constant load but changes the network cases' findings "
                "(docs/design_notes.md sections 41 and 48)"},
               &NumericsConfig::friction_at_solution),
       boolean({"failures_on_settled_contacts", "", "none (HFDDA): the seed checks contact states and bond failures in the same round (2.3)",
                "true: a bond may fail only in an open-close round in which no contact changes state, so "
                "that every failure is judged on a state whose contacts are settled (docs/design_notes.md "
                "section 34); false: the seed's rounds, failures and contact changes together"},
               &NumericsConfig::failures_on_settled_contacts),
       number({"tie_tolerance", "-", "§2.3 (iii): 0.1 %",
               "relative difference of normal stress below which simultaneous tensile "
               "failures both break"},
              &NumericsConfig::tie_tolerance, positive_up_to(1)),
       boolean({"shear_failure_of_intact_joints", "", "§2.3 (ii)",
                "false: intact joints must fail in tension before they may shear"},
               &NumericsConfig::shear_failure_of_intact_joints),
       number({"min_width_main", "m", "§2.1: 0.5 um",
               "smallest aperture of a wetted joint away from the fracture tips"},
              &NumericsConfig::min_width_main_m, positive_up_to(1), ">= min_width_tip"),
       number({"min_width_tip", "m", "§2.1: 0.1 um",
               "smallest aperture of a wetted joint at a fracture tip"},
              &NumericsConfig::min_width_tip_m, positive_up_to(1), "<= min_width_main"),
       number({"max_closing_fraction", "-", "§2.1: 5 %",
               "largest fraction of its aperture a wetted joint may close in one step"},
              &NumericsConfig::max_closing_fraction, interval(0, true, 1, true)),
       number({"coupling_tolerance", "-", "§2.4, eqs. 2.25-2.26 (erratum 2 in docs/seed_errata.md)",
               "coupled-step stop: relative pressure change and relative mass residual "
               "below it"},
              &NumericsConfig::coupling_tolerance, positive_up_to(1)),
       choice({"flow_jacobian", "", "none (HFDDA)",
               "linear solves of the flow Newton iteration: dense (the aperture sensitivity S formed, "
               "one solve per wetted node, and the Jacobian factorised densely), krylov (S as an operator, "
               "one solve per product, GMRES with a two-level preconditioner; memory and cost grow with the "
               "network, not its square; it pays off only where the flow Newton needs few iterations), augmented (S "
               "as an operator, each Newton step one sparse LU of the flow balance together with the block "
               "displacements, UMFPACK; no Krylov iteration; design notes section 46), auto "
               "(dense below 2,500 wetted nodes, augmented from there, where the scaling benchmark measured it "
               "faster; dense throughout with aperture_response: converged_contacts; design notes sections 43 and 46)"},
              &NumericsConfig::flow_jacobian,
              Choices<FlowJacobianKind>{{"dense", FlowJacobianKind::dense},
                                        {"krylov", FlowJacobianKind::krylov},
                                        {"augmented", FlowJacobianKind::augmented},
                                        {"auto", FlowJacobianKind::automatic}}),
       boolean({"inexact_flow_solves", "", "none (HFDDA)",
                "on the Krylov path (flow_jacobian krylov): true, GMRES stops "
                "at 1e-4 of the residual while the line-search flow Newton converges well (its first iteration, "
                "or its last step taken whole and the mass residual at least halved) and at 1e-10 otherwise and "
                "in the full-step and pseudo-transient fallbacks; false, always at 1e-10. No effect on the dense "
                "path, which solves exactly (docs/design_notes.md section 43)"},
               &NumericsConfig::inexact_flow_solves),
       choice({"aperture_response", "", "none (HFDDA)",
               "with method alm: the response of the wetted joints' apertures to the fluid pressures that "
               "the flow solve uses. fixed_multipliers: K with the contact multipliers of the current "
               "iteration held, which at a crack tip or along a locked joint lets the faces open by the "
               "springs' compliance that the next multiplier updates take back; converged_contacts: K with "
               "the iterated springs 100 times stiffer, the response once the multipliers have converged, "
               "about which the flow solve linearises at each iteration (one more factorisation per change "
               "of K; design notes section 19)"},
              &NumericsConfig::aperture_response,
              Choices<ApertureResponse>{{"fixed_multipliers", ApertureResponse::fixed_multipliers},
                                        {"converged_contacts", ApertureResponse::converged_contacts}}),
       choice({"fluid_load", "", "§2.4: linear pressure along each face",
               "how the fluid pressure on a joint's faces loads the blocks: integrated (the linear pressure "
               "along each face integrated exactly) or lumped (each end's pressure as a force L p / 2 at its "
               "corner, the load work-conjugate to the flow network's nodal volumes L w / 2, which makes the "
               "flow Jacobian's volume part symmetric; design notes section 19)"},
              &NumericsConfig::fluid_load,
              Choices<FluidLoad>{{"integrated", FluidLoad::integrated}, {"lumped", FluidLoad::lumped}}),
       integer({"max_coupling_iterations", "", "§2.4", "pressure iterations per coupled solve"},
               &NumericsConfig::max_coupling_iterations, interval(1, false, kMaxIterations, false)),
       integer({"max_step_cuts", "", "",
                "times a step that fails to converge is retried with dt halved before the "
                "run stops"},
               &NumericsConfig::max_step_cuts, interval(0, false, 30, false),
               "dt / 2^30 is about 1e-9 dt")}};
  return table;
}

const Table<FractureCriterionConfig>& fracture_criterion_table() {
  static const Table<FractureCriterionConfig> table{
      "`fracture`",
      "How intact joints fail. `strength`: the seed's rule everywhere (tension N > T0 Lc, seed 2.3; "
      "`joints.fracture_toughness` maps K_IC to T0 by eq. 4.13). `energy_release_rate`: a joint still bonded "
      "at a crack tip (a point where a broken joint ends) fails when G_I / G_IC + G_II / G_IIC >= 1, with G_I "
      "and G_II from the contact forces of the joint ahead and the opening and slip of the broken joint behind "
      "by virtual crack closure, G_C = K_C^2 (1 - nu^2) / E; the joint that fails is the breakable one nearest "
      "the direction of maximum hoop stress. Bonds away from crack tips (an uncracked body, crack faces) keep "
      "the strength rule (T0, C0), and a failure in tension opens its whole joint. docs/formulation.md section 5.",
      {choice({"criterion", "", "§2.3 (strength); none (HFDDA) for energy_release_rate",
               "strength or energy_release_rate"},
              &FractureCriterionConfig::criterion,
              Choices<FailureCriterionKind>{{"strength", FailureCriterionKind::strength},
                                            {"energy_release_rate", FailureCriterionKind::energy_release_rate}}),
       choice({"crack_closure", "", "none (HFDDA)",
               "energy_release_rate: one_joint (the joint ahead closed against the joint behind) or extrapolated "
               "(one and two joints of closure, extrapolated to a vanishing joint: removes the O(L / a) error of "
               "one joint; one joint where no straight second joint lies behind)"},
              &FractureCriterionConfig::crack_closure,
              Choices<CrackClosureKind>{{"one_joint", CrackClosureKind::one_joint},
                                        {"extrapolated", CrackClosureKind::extrapolated}}),
       optional_number({"fracture_toughness", "Pa m^0.5", "§4.5: K_IC = 0.886 and 4.43 MPa m^0.5 (erratum 7)",
                        "energy_release_rate: Mode I toughness K_IC at crack tips"},
                       &FractureCriterionConfig::fracture_toughness_Pa_sqrt_m, positive_up_to(kMaxStrength),
                       "none; required with energy_release_rate"),
       optional_number({"mode2_toughness", "Pa m^0.5", "", "energy_release_rate: Mode II toughness K_IIC"},
                       &FractureCriterionConfig::mode2_toughness_Pa_sqrt_m, positive_up_to(kMaxStrength),
                       "fracture_toughness")}};
  return table;
}

const Table<TimeConfig>& time_table() {
  static const Table<TimeConfig> table{
      "`time`",
      "",
      {number({"dt", "s", "Table 3.1: 1 s; Table 5.3: 1 min", "time step"}, &TimeConfig::dt_s,
              positive_up_to(kMaxTime)),
       number({"end_time", "s", "§3.1: 2 steps; Table 4.1: 10 s; Table 5.3: 1 hr",
               "simulated time"},
              &TimeConfig::end_time_s, positive_up_to(kMaxTime),
              ">= time.dt, a whole number of steps of time.dt, at most 1e7 steps"),
       choice({"stop_when", "", "§5.2: a laboratory block, whose fluid escapes at its edge",
               "none: run to end_time; fluid_at_edge: end after the first step in which a joint holding fluid "
               "touches the boundary of domain.inner (the edge of the block being fractured); needs a `fluid`"},
              &TimeConfig::stop_when,
              Choices<std::string>{{"none", "none"}, {"fluid_at_edge", "fluid_at_edge"}})}};
  return table;
}

}  // namespace hfdda::io
