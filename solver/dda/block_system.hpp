#pragma once
// The DDA block system (seed sections 2.2-2.3): blocks with Shi's six unknowns,
// accumulated block stresses, joint contacts with penalty or Augmented Lagrangian
// springs, and the pieces of one time step's open-close iterations.
//
// Each step minimises the total potential energy
//   Pi(D) = sum_blocks [ A/2 eps^T C eps + A sigma^T eps + (rho/dt^2) D^T G D - loads ]
//         + sum_springs w [ lambda g(D) + k/2 g(D)^2 ]             (eqs. 2.13-2.22)
// over the step displacements D, i.e. solves K D = F (eq. 2.12) with the spring set
// fixed by the contact states; the open-close loop changes states until none changes.
//
// The loop itself belongs to coupling::CoupledStep, which calls, in this order:
//   begin_step(dt)                      geometry, block terms, spring linearisations
//   repeat {
//     assemble_and_factorise()          K for the current states (when they changed)
//     begin_contact_iterations(); repeat { contact_rhs() -> solver().solve() ->
//       update_multipliers() }          ALM (Uzawa, eq. 2.19) or one penalty solve, repeated
//                                       while the friction of held springs follows N
//     trial_contacts(d)                 tractions and open-close rules at the trial D
//     apply_state_changes(d, changes)   with the bond failures found by fracture/
//   }
//   commit(d, dt)  or  roll_back()      (a failed step leaves the committed state)

#include <optional>
#include <string>
#include <vector>

#include "core/anderson_acceleration.hpp"
#include "core/step_statistics.hpp"
#include "dda/block_loads.hpp"
#include "dda/block_sparse_matrix.hpp"
#include "dda/block_state.hpp"
#include "dda/contact_set.hpp"
#include "dda/contacts.hpp"
#include "mesh/mesh.hpp"

namespace hfdda {
class BinaryWriter;
class BinaryReader;
}  // namespace hfdda

namespace hfdda::dda {

struct Material {
  double youngs_modulus_Pa = 25.0e9;
  double poissons_ratio = 0.25;
  double density_kg_m3 = 2650.0;
};

struct MechanicsSettings {
  bool augmented_lagrangian = true;         ///< false: penalty method
  /// With the Augmented Lagrangian: iterate the multipliers of intact (bonded) joint
  /// contacts only; contacts whose bond has broken (sliding, re-closed) and vertex-vertex
  /// contacts keep theirs fixed within the step, as penalty springs (seed 5.1).
  bool two_tier_contacts = false;
  /// With two-tier contacts: the springs of the iterated (intact) contacts are this many
  /// times k_n and k_s; k_n and k_s are then the penalty springs of the others. An
  /// iterated spring only sets the pace of the Uzawa iterations (its converged gap is
  /// zero whatever its stiffness); as stiff as the penalty springs next to it, it
  /// converges at a rate set by their ratio (docs/design_notes.md section 21).
  double intact_stiffness_ratio = 100.0;
  double normal_stiffness_N_m = 2.5e12;     ///< k_n
  double shear_stiffness_N_m = 2.5e12;      ///< k_s
  double fixed_point_stiffness_N_m = 2.5e12;
  double vertex_vertex_activation_m = 1.0e-6;
  double alm_force_tolerance = 1.0e-7;
  int max_alm_iterations = 200;
  int max_open_close_iterations = 200;
  /// Cycle detection (seed 5.1): a contact changing state more often than this within
  /// a step is set to the most open state it had in the step and held there.
  int max_state_flips = 6;
  /// How a cycle is resolved for a joint contact whose most open state is open but whose
  /// faces would then pass through each other by more than kCycleHoldPenetration of the
  /// joint's length: false, held open all the same (the seed's rule); true, closed and held
  /// at sliding for the rest of the step (docs/design_notes.md section 25).
  bool close_penetrating_cycles = false;
  /// A joint contact whose bond broke earlier in this step and that slides: true, locked
  /// again as soon as its slip since the failure reverses (DDA's rule for any sliding
  /// contact); false, left sliding for the rest of the step (opening still opens it), the
  /// reversal being judged again from the next step. The slip is measured from the
  /// failure, so within the failing step a reversal is the rebound of the neighbours'
  /// redistribution, and the re-locked contact holds a shear force outside friction that
  /// may break the next bond (docs/design_notes.md section 29).
  bool relock_in_failure_step = true;
  /// Sliding contacts whose springs are held through the step (penalty contacts, two-tier
  /// contacts' unbonded ones): true, friction acts with the normal force of the contact
  /// iterate (iterated to 0.1 %) and a contact closed at the step's start re-locks when its
  /// slip in the step reverses, where it was at the start; false, the normal force at the
  /// step's start and re-locking once the slip since the last lock reverses (the default:
  /// true changes the network cases' findings, docs/design_notes.md section 41).
  bool friction_at_solution = false;
  /// A step whose contact iterations end with two faces of a joint overlapping by more
  /// than this fraction of the joint's length is not accepted (it is cut): no rock mass
  /// deforms that much, so the contact state it ended on, e.g. a cycle held open while
  /// its faces pass through each other, is not a solution (docs/design_notes.md
  /// section 24; Shi's DDA cuts the time step on its penetration limit likewise).
  double max_overlap_fraction = 0.1;
  /// A step whose displacement strains a block by more than this (principal strain
  /// increment) is not accepted either: an elastic rock block strained 10 % in one step
  /// carries stresses of E / 10, far beyond any rock strength, and such strains come from
  /// faces that were driven through each other, not from loads; a block strained by -1
  /// is inverted and makes K indefinite at the next factorisation (design notes
  /// section 30).
  double max_step_strain = 0.1;
  bool dynamic = false;                     ///< false: velocities reset every step (static)
  /// Static analysis: blocks that the contact state of an open-close iteration does not
  /// hold (a group whose closed contacts leave it a rigid motion) take the inertia term
  /// of this time instead of the step's, which bounds their motion; the rest of the rock
  /// mass keeps 2 M / dt^2 (mechanism_holds.cpp; docs/design_notes.md section 25) [s].
  double mechanism_inertia_time_s = 0.1;
  /// Within a step, the springs that the contact-state changes of an open-close iteration
  /// add to K or remove from it are applied to the step's factorisation as a low-rank
  /// correction (Woodbury identity, SpdSolver::modify) instead of a new factorisation,
  /// up to BlockSystem::kMaxLowRank springs (docs/design_notes.md section 26).
  bool low_rank_updates = false;
  /// With the Augmented Lagrangian: > 1, a coupled fluid model takes the apertures'
  /// response to its pressures from K with the iterated springs this many times stiffer
  /// (the response of the converged contact problem) rather than from K at fixed
  /// multipliers; one more factorisation per change of K (docs/design_notes.md section 19).
  /// 0 or 1: off.
  double converged_response_stiffening = 0.0;
  /// Fluid pressure on joint faces as forces L p / 2 at the corners (trapezoidal rule)
  /// rather than integrated exactly along the face (design notes section 19).
  bool lumped_fluid_load = false;
  bool converged_response() const { return augmented_lagrangian && converged_response_stiffening > 1.0; }
};

/// Linearised normal separation of a joint's faces at one end, the mean of the
/// symmetric spring pair: gap(D) = gap0 + row_a . D_a + row_b . D_b  [m].
struct JointEndGap {
  int block_a = -1, block_b = -1;
  Row6 row_a = Row6::Zero(), row_b = Row6::Zero();
  double gap0_m = 0.0;
};

/// What one multiplier update of the contact iterations concluded.
enum class ContactIteration { converged, stalled, again };

/// Mean gap and forces of a contact's springs at a trial displacement (tension positive).
struct ContactTraction {
  double gap_m = 0.0, normal_N = 0.0, shear_N = 0.0;
};

/// A state change of one contact, applied by apply_state_changes().
struct ContactChange {
  ContactChange(int contact_index, ContactState to_state, bool breaks = false, double sign = 0.0,
                std::optional<VertexEdgeSpring> spring = std::nullopt)
      : contact(contact_index), to(to_state), breaks_bond(breaks), friction_sign(sign), vertex_vertex(spring) {}
  int contact;
  ContactState to;
  bool breaks_bond;
  double friction_sign;  ///< +-1: sense of the friction force from now on; 0: unchanged
  std::optional<VertexEdgeSpring> vertex_vertex;  ///< spring of an activated vertex-vertex contact
  /// A sliding contact whose slip in this step reversed locks where it was at the step's
  /// start (its reference and shear multiplier then), not where the trial left it.
  bool relock_at_step_start = false;
};

/// The joint contacts at a trial displacement.
struct OpenCloseTrial {
  std::vector<ContactTraction> tractions;  ///< per joint contact
  /// Open-close changes of the joint contacts, in contact order; intact bonds are
  /// left to the fracture criteria.
  std::vector<ContactChange> changes;
};

class BlockSystem {
 public:
  BlockSystem(const mesh::Mesh& mesh, std::vector<Material> materials, MechanicsSettings settings);

  // --- loads and constraints (SI, per metre of out-of-plane thickness) -----------
  void add_fixed_point(const Vec2& at);
  void add_point_load(const Vec2& at, const Vec2& force_N);
  void set_body_force(const Vec2& force_N_m3) { loads_.body_force = force_N_m3; }
  /// Far-field stress acting on a boundary edge as the traction t = sigma . n of its
  /// current outward normal (a follower load: self-equilibrated on any closed boundary,
  /// so a body held at one point does not rotate under it), integrated exactly.
  void add_boundary_stress(int boundary_edge, const Eigen::Matrix2d& stress_Pa);
  /// A far-field stress pattern (per unit of the load level, dimensionless) on a boundary
  /// edge, applied like add_boundary_stress scaled by the level of set_load_level().
  void add_ramped_boundary_stress(int boundary_edge, const Eigen::Matrix2d& stress_per_Pa);
  /// Load level of the ramped boundary stresses from the next step on [Pa].
  void set_load_level(double level_Pa) { loads_.ramp_level_Pa = level_Pa; }
  double load_level() const { return loads_.ramp_level_Pa; }
  /// In-situ stress: every block starts with `stress_Pa` and every closed joint contact
  /// with the matching traction (times its length) as its contact force, so that with
  /// the same stress on the whole outer boundary the system is in equilibrium at rest.
  /// Call before the first step, after the boundary stresses.
  void set_in_situ_stress(const Eigen::Matrix2d& stress_Pa);

  // --- one time step (driven by coupling::CoupledStep) ---------------------------
  /// Geometry, block terms and the block loads of the step, spring linearisations.
  void begin_step(double dt_s);
  /// The block loads F of the step without the contact terms; models coupled with the
  /// blocks add their loads here after begin_step (e.g. prescribed fluid pressure).
  Eigen::VectorXd& step_loads() { return step_loads_; }
  /// K for the current contact states, factorised (statistics: assembly, factorisation).
  void assemble_and_factorise(StepStatistics& stats);
  /// The factorisation of the last assemble_and_factorise().
  const SpdSolver& solver() const { return solver_; }
  /// K with the springs of the iterated (Augmented Lagrangian) contacts
  /// converged_response_stiffening times stiffer, factorised: with them stiff, K^-1 approaches the response of the
  /// converged contact problem, whose constrained gaps do not move (the multipliers'
  /// updates included), for a coupled model that must anticipate it (docs/design_notes.md
  /// section 19). Refactorised on each call (statistics: factorisations).
  void factorise_converged_response(StepStatistics& stats);
  const SpdSolver& converged_response_solver() const { return stiffened_solver_; }
  /// Start of the contact iterations of one open-close iteration.
  void begin_contact_iterations();
  /// Right-hand side F + contact terms with the current multipliers (eqs. 2.19-2.22).
  Eigen::VectorXd contact_rhs() const;
  /// Uzawa update of the multipliers from the displacement of this iteration (0-based).
  /// Penalty: converged at once. Throws ConvergenceError at the iteration limit.
  ContactIteration update_multipliers(const Eigen::VectorXd& d, int iteration, StepStatistics& stats);
  /// Tractions of the joint contacts and their open-close changes at a trial displacement.
  OpenCloseTrial trial_contacts(const Eigen::VectorXd& d, StepStatistics& stats) const;
  /// Applies the joint-contact changes (in the order given), judges and applies the
  /// vertex-vertex contacts on the joint states they lead to; returns the count applied.
  int apply_state_changes(const Eigen::VectorXd& d, const std::vector<ContactChange>& joint_changes,
                          StepStatistics& stats);
  /// The first change of the last apply_state_changes(), for error messages.
  const std::string& first_change() const { return first_change_; }
  /// Accepts the step's displacement: stresses, corners, velocities, attachments.
  void commit(const Eigen::VectorXd& d, double dt_s, StepStatistics& stats);
  /// Contacts back to the start of the step (nothing of the step is committed).
  void roll_back();

  // --- for coupled models, valid during a step ---------------------------------------
  /// Adds the block forces of a pressure varying linearly from pressure_p (at the
  /// joint's point p) to pressure_q, acting on both faces of the joint.
  void add_joint_pressure_load(int joint, double pressure_p_Pa, double pressure_q_Pa, Eigen::VectorXd& forces) const;
  JointEndGap joint_end_gap(int joint, int end) const;
  /// The joint end whose faces overlap most, relative to the joint's length, at the
  /// trial displacement d (linearised gaps); overlap 0 and joint -1 if none does.
  struct FaceOverlap {
    double overlap_m = 0.0, fraction_of_length = 0.0;
    int joint = -1, end = 0;
  };
  FaceOverlap largest_face_overlap(const Eigen::VectorXd& d) const;
  /// The block with the largest principal strain increment (in magnitude) in the trial
  /// displacement d; strain 0 and block -1 for a model without blocks.
  struct BlockStrain {
    double strain = 0.0;
    int block = -1;
  };
  BlockStrain largest_step_strain(const Eigen::VectorXd& d) const;
  /// The largest tension [Pa: normal force over the contact's length] on a closed joint
  /// contact whose bond is broken, at the trial displacement d; 0 if none pulls. The
  /// contact law allows none (the open-close check opens it), so a committed state with one
  /// normally holds a contact that the cycle rule kept closed; growing from step to step,
  /// it came before the collapses of design notes section 49.
  double largest_unbonded_tension_Pa(const Eigen::VectorXd& d) const;

  // --- state queries --------------------------------------------------------------
  const mesh::Mesh& mesh() const { return mesh_; }
  int n_blocks() const { return blocks_.n_blocks(); }
  const std::vector<Contact>& contacts() const { return contacts_.all(); }
  /// Contacts of a joint: indices of its end at p and at q.
  std::array<int, 2> joint_contacts(int joint) const { return {2 * joint, 2 * joint + 1}; }
  /// Contact state of a joint's end 0 (at point p) or 1 (at point q).
  ContactState joint_end_state(int joint, int end) const { return contacts_.all()[joint_contacts(joint)[end]].state; }
  /// The joint's other end or another joint contact at its point is open (seed 2.3 i).
  bool has_open_neighbour(int contact) const { return contacts_.has_open_neighbour(contact); }
  /// The joint's other end or another joint contact at its point is open or unbonded (seed 5.1).
  bool has_failed_neighbour(int contact) const { return contacts_.has_failed_neighbour(contact); }
  /// Current corner position of a block.
  Vec2 corner(int block, int local) const { return blocks_.corner(block, local); }
  int n_corners(int block) const { return blocks_.n_corners(block); }
  /// Centroid of a block at the start of the step [m].
  Vec2 centroid(int block) const { return moments_[block].centroid; }
  Vec2 initial_corner(int block, int local) const {
    return blocks_.initial_corners[blocks_.corner_offset[block] + local];
  }
  const Eigen::Vector3d& stress(int block) const { return blocks_.stress[block]; }
  const std::vector<int>& block_material() const { return blocks_.material; }
  /// Normal separation of the two faces of a joint at one end (mean of its springs) [m].
  double joint_gap(int joint, int end) const;
  /// Contact normal and shear force (tension positive) of a contact at the committed state [N].
  std::pair<double, double> contact_forces(int contact) const;
  /// Displacement of block b's face relative to block a's at a joint's end 0 (point p) or
  /// 1 (point q) since t = 0, their corners there [m]: at the committed state, or with
  /// the step displacement `d` of the current step added (non-empty d: during a step).
  Vec2 joint_end_separation(int joint, int end, const Eigen::VectorXd& d = {}) const;
  /// Displacement of each block in the last committed step.
  const std::vector<Vec6>& last_step_displacement() const { return blocks_.last_d; }
  int total_vertex_vertex_activations() const { return total_vv_activations_; }
  const MechanicsSettings& settings() const { return settings_; }
  const std::vector<Material>& materials() const { return materials_; }

  /// Committed state (blocks, contacts with their multipliers and shear references,
  /// vertex-vertex activations, attachment positions, load level) for a checkpoint;
  /// restore_state() into a system built from the same mesh and settings continues
  /// bit for bit (block_system_state.cpp). Throws std::runtime_error on a mismatch.
  void save_state(BinaryWriter& out) const;
  void restore_state(BinaryReader& in);

  /// Blocks of groups that the current contact state does not hold: joined by joints
  /// locked at both ends, with no fixed point, and left a rigid motion by their closed
  /// contacts to other groups (in a model without fixed points the largest group, the
  /// rock mass held by its far-field loads, does not count).
  std::vector<int> mechanism_blocks() const;

  /// The assembled matrix of the last open-close iteration (the augmented flow system,
  /// coupling/augmented_flow_system.hpp; tests, benchmarks).
  const BlockSparseMatrix& stiffness() const { return stiffness_; }
  /// Number of the K of the last assemble_and_factorise(): every assembly counts one.
  int stiffness_version() const { return stiffness_version_; }
  /// The spring terms by which K changed from version `since` to the current one (a
  /// negative stiffness removes a spring; low_rank_updates.cpp). False when K changed in
  /// another way as well (a new step's block terms, the mechanism holds) or `since` is
  /// not a version of this step: a model keeping products with K^-1 must then redo them.
  bool spring_changes_since(int since, std::vector<SpringTerm>& changes) const;

 private:
  // block_loads.cpp
  int block_containing(const Vec2& p) const;
  void update_block_geometry();
  void assemble_block_terms(double dt_s);
  void add_attachment_loads();
  // contact_iterations.cpp
  /// (Re)builds K's pattern from the joints and the active vertex-vertex contacts; a
  /// new symbolic analysis follows at the next factorisation.
  void rebuild_pattern();
  void linearise_spring(VertexEdgeSpring& s) const;
  void linearise_contacts();
  void assemble_contacts();
  // mechanism_holds.cpp
  /// A group's rigid motion is free when the smallest eigenvalue of its springs' rigid
  /// stiffness is below this fraction of the largest.
  static constexpr double kMechanismStiffnessRatio = 1e-6;
  /// close_penetrating_cycles: the trial penetration, as a fraction of the joint's length,
  /// beyond which a cycle-held open contact is closed instead (sections 25 and 39): about
  /// what a closed contact carrying 20 MPa at k_n = 30 E of shale would penetrate, so an
  /// open contact held through its faces by more is no state a closed one would reach.
  static constexpr double kCycleHoldPenetration = 1e-5;
  /// Adds the mechanism inertia to K for the blocks of mechanism_blocks().
  void hold_mechanisms();
  // low_rank_updates.cpp
  /// Springs changed by one assembly above which K is factorised anew: W = K0^-1 C for
  /// r springs took 9, 17 and 100 ms for r = 2, 8 and 32 against 40 ms for a
  /// factorisation of the KGD case's K at dx = 0.5 m (BM_LowRankK, section 26).
  static constexpr int kMaxLowRankPerAssembly = 16;
  /// Springs changed since the last factorisation above which K is factorised anew:
  /// each solve then carries a correction of that rank (a 64-column solve: +27 % at 32).
  static constexpr int kMaxLowRank = 32;
  /// |K x - b| / |b| of a check solve above which a corrected factorisation is dropped;
  /// a solve with a new factorisation of the KGD case's K leaves 1e-9 (section 26).
  static constexpr double kLowRankResidual = 1e-7;
  /// Iterates of the friction normal forces that their acceleration combines: a wedge of
  /// a few sliding contacts is a fixed point of as many coupled forces.
  static constexpr int kFrictionAccelerationDepth = 5;
  /// A contact's spring terms in K: normal (2 k) and shear (2 k + 1) of its springs k.
  struct ContactTerms {
    std::array<SpringTerm, 4> term;
    std::array<bool, 4> present{};
  };
  ContactTerms contact_terms(const Contact& c) const;
  /// Before a change to contact `ci` within a step: keeps its terms as last assembled.
  void remember_assembled_terms(int ci);
  /// After an assembly: the spring terms it changed, appended to the step's log.
  void log_spring_changes();
  /// Applies the spring changes of the last assembly to the factorisation when they are
  /// few and nothing else of K changed; false: K must be factorised.
  bool modify_factor(StepStatistics& stats);
  double spring_gap(const VertexEdgeSpring& s, const Eigen::VectorXd& d) const;
  double spring_shear(const VertexEdgeSpring& s, const Eigen::VectorXd& d) const;
  [[noreturn]] void throw_alm_limit(double error, double scale) const;
  /// Sets the friction normal force of every sliding contact with held springs to its
  /// value at `d`; true if one moved by more than the tolerance since the last iterate.
  bool follow_friction_normal_forces(const Eigen::VectorXd& d);
  /// Forgets the friction fixed point's history (a new contact solve or set of contacts).
  void restart_friction_fixed_point();
  /// matrix += stiffness e e^T for the spring term's e (the slot of its block pair).
  static void add_spring_term(BlockSparseMatrix& matrix, int slot, const SpringTerm& t, double stiffness);
  /// The contact's multipliers are iterated (Augmented Lagrangian) rather than held (two-tier penalty).
  bool iterated(const Contact& c) const { return !settings_.two_tier_contacts || (c.joint >= 0 && c.bonded); }
  /// k_n and k_s of this contact's springs: times intact_stiffness_ratio for the iterated
  /// contacts of two-tier contacts (MechanicsSettings).
  double stiffness_scale(const Contact& c) const {
    return settings_.two_tier_contacts && settings_.augmented_lagrangian && iterated(c)
               ? settings_.intact_stiffness_ratio
               : 1.0;
  }
  double normal_stiffness(const Contact& c) const { return settings_.normal_stiffness_N_m * stiffness_scale(c); }
  double shear_stiffness(const Contact& c) const { return settings_.shear_stiffness_N_m * stiffness_scale(c); }
  // open_close.cpp
  ContactTraction trial_traction(const Contact& c, const Eigen::VectorXd& d, StepStatistics& stats) const;
  std::optional<ContactChange> open_close_change(int contact, const ContactTraction& t, const Eigen::VectorXd& d) const;
  /// " at the <unknown> of block b (centroid, signed area, K's diagonal)", for errors.
  std::string describe_unknown(int unknown) const;
  void add_vertex_vertex_changes(const Eigen::VectorXd& d, std::vector<ContactChange>& changes, StepStatistics& stats);
  void apply_change(const ContactChange& change, const Eigen::VectorXd& d, StepStatistics& stats);
  void describe_first_change(const Contact& c, ContactState to);
  /// Spring to activate if a corner of a vertex-vertex candidate penetrates deeper than
  /// the activation tolerance (seed 2.3 vi); std::nullopt otherwise.
  std::optional<VertexEdgeSpring> vertex_vertex_spring(const Contact& c, const Eigen::VectorXd& d,
                                                       double& max_penetration) const;
  void reset_shear_reference(VertexEdgeSpring& s, const Eigen::VectorXd& d) const;
  Vec2 displaced(int block, const Vec2& p, const Eigen::VectorXd& d) const;

  mesh::Mesh mesh_;
  std::vector<Material> materials_;
  MechanicsSettings settings_;
  BlockState blocks_;
  ExternalLoads loads_;
  ContactSet contacts_;
  double gap_round_off_m_ = 0.0;  // gaps below this are round-off of the coordinates
  int total_vv_activations_ = 0;
  double step_dt_s_ = 0.0;        // the step's dt, for the mechanism inertia
  std::vector<int> held_blocks_;  // mechanism blocks held by the last assembly

  // Per-step block terms.
  std::vector<PolygonMoments> moments_;
  std::vector<Mat6> block_matrix_;
  Eigen::VectorXd step_loads_;

  // Open-close and contact iterations of the current step.
  std::string first_change_;     // first state change of the last open-close check
  std::vector<ContactState> next_joint_state_;  ///< joint states after this round's changes
  std::vector<double> alm_corrections_, alm_previous_corrections_;  ///< k g, k s per contact
  int alm_worst_contact_ = -1;   // contact of the largest correction
  // The friction normal forces of held sliding contacts within one contact solve, as a
  // fixed point accelerated over its last iterates (follow_friction_normal_forces).
  AndersonAcceleration friction_acceleration_{kFrictionAccelerationDepth};
  std::vector<int> friction_contacts_;  // the contacts of its vector, in order
  bool friction_accelerated_ = false;   // the plain iteration stopped contracting
  double friction_residual_N_ = -1.0;   // |G(N) - N| of the last iterate (-1: none yet)
  std::vector<int> friction_scratch_contacts_;           // this iterate's contacts
  std::vector<double> friction_used_N_, friction_now_N_;  // N and G(N) of this iterate

  BlockSparseMatrix stiffness_;
  SpdSolver solver_;
  BlockSparseMatrix stiffened_;   // K with the iterated springs stiffened
  SpdSolver stiffened_solver_;
  // What the factorisation in solver_ (with its low-rank changes) is of.
  bool factor_of_this_step_ = false;
  std::vector<int> factorised_held_blocks_;
  // How K changed within the step (low_rank_updates.cpp): the terms of the contacts
  // changed since the last assembly, and the log of spring changes of the step's
  // assemblies, each with the version of K it led to. The log holds every change of K
  // after version logged_from_version_ (-1: none yet in this step).
  std::vector<std::pair<int, ContactTerms>> assembled_terms_;  // of contacts changed since
  std::vector<char> terms_remembered_;                          // per contact
  std::vector<SpringTerm> spring_log_;
  std::vector<int> spring_log_version_;
  int stiffness_version_ = 0;
  int logged_from_version_ = -1;
  std::vector<int> assembled_held_blocks_;  // the mechanism holds of the last assembly
};

}  // namespace hfdda::dda
