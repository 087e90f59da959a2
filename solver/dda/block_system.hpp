#pragma once
// The DDA block system (seed sections 2.2-2.3): blocks with Shi's six unknowns,
// accumulated block stresses, joint contacts with penalty or Augmented Lagrangian
// springs, and the open-close iterations of one time step.
//
// Each step minimises the total potential energy
//   Pi(D) = sum_blocks [ A/2 eps^T C eps + A sigma^T eps + (rho/dt^2) D^T G D - loads ]
//         + sum_springs w [ lambda g(D) + k/2 g(D)^2 ]             (eqs. 2.13-2.22)
// over the step displacements D, i.e. solves K D = F (eq. 2.12) with the spring set
// fixed by the contact states; the open-close loop changes states until none changes.
//
// Lifecycle of a step: begin (geometry, block terms, spring linearisations) ->
// repeat { assemble K for the states -> factorise -> ALM solves -> check states }
// -> commit (stresses, corners). A step that does not converge throws
// ConvergenceError and leaves the committed state untouched.

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/step_statistics.hpp"
#include "dda/block_sparse_matrix.hpp"
#include "dda/contacts.hpp"
#include "mesh/mesh.hpp"

namespace hfdda::dda {

struct Material {
  double youngs_modulus_Pa = 25.0e9;
  double poissons_ratio = 0.25;
  double density_kg_m3 = 2650.0;
};

struct MechanicsSettings {
  bool augmented_lagrangian = true;         ///< false: penalty method
  double normal_stiffness_N_m = 2.5e12;     ///< k_n
  double shear_stiffness_N_m = 2.5e12;      ///< k_s
  double fixed_point_stiffness_N_m = 2.5e12;
  double vertex_vertex_activation_m = 1.0e-6;
  double alm_force_tolerance = 1.0e-7;
  int max_alm_iterations = 200;
  int max_open_close_iterations = 200;
  double tie_tolerance = 1.0e-3;
  bool shear_failure_of_intact_joints = false;
  /// Seed 2.3 (i): a bond may fail only next to an open contact and a pressurised point.
  bool failure_needs_open_neighbour_and_fluid = true;
  bool dynamic = false;                     ///< false: velocities reset every step (static)
};

class BlockSystem;

/// A model coupled with the blocks inside their time step (the fluid network, seed
/// 2.4). The block system calls it at fixed points of the step:
///   begin -> { [K factorised] prepare -> (solve per ALM iteration) -> update_states }
///   -> commit, or abort if the step fails.
/// solve() receives the displacement for the mechanical loads alone and returns the
/// coupled one (its own loads added through the factorised K).
class StepCoupling {
 public:
  virtual ~StepCoupling() = default;
  virtual void begin_step(const BlockSystem& system, double dt_s) = 0;
  /// K or the coupled model's own set changed since the last call (factorised K given).
  virtual void prepare(const BlockSystem& system, const SpdSolver& solver, bool stiffness_changed) = 0;
  virtual Eigen::VectorXd solve(const BlockSystem& system, const SpdSolver& solver,
                                const Eigen::VectorXd& mechanical_displacement) = 0;
  /// After the contact-state update: changes of the coupled model's own states.
  virtual int update_states(const BlockSystem& system) = 0;
  /// Points where the coupled fluid is pressurised now (propagation rule 2.3 i).
  virtual const std::vector<char>& pressurised_points() const = 0;
  virtual void commit(const BlockSystem& system) = 0;
  virtual void abort() = 0;
};

/// Linearised normal separation of a joint's faces at one end, the mean of the
/// symmetric spring pair: gap(D) = gap0 + row_a . D_a + row_b . D_b  [m].
struct JointEndGap {
  int block_a = -1, block_b = -1;
  Row6 row_a = Row6::Zero(), row_b = Row6::Zero();
  double gap0_m = 0.0;
};

class BlockSystem {
 public:
  BlockSystem(const mesh::Mesh& mesh, std::vector<Material> materials, MechanicsSettings settings);

  // --- loads and constraints (SI, per metre of out-of-plane thickness) -----------
  void add_fixed_point(const Vec2& at);
  void add_point_load(const Vec2& at, const Vec2& force_N);
  void set_body_force(const Vec2& force_N_m3) { body_force_ = force_N_m3; }
  /// Far-field stress acting on a boundary edge as the traction t = sigma . n of its
  /// current outward normal (a follower load: self-equilibrated on any closed boundary,
  /// so a body held at one point does not rotate under it), integrated exactly.
  void add_boundary_stress(int boundary_edge, const Eigen::Matrix2d& stress_Pa);
  /// In-situ stress: every block starts with `stress_Pa` and every closed joint contact
  /// with the matching traction (times its length) as its contact force, so that with
  /// the same stress on the whole outer boundary the system is in equilibrium at rest.
  /// Call before the first step, after the boundary stresses.
  void set_in_situ_stress(const Eigen::Matrix2d& stress_Pa);
  /// Fluid pressure at the geometric points and which joints are filled with fluid;
  /// wetted joints carry the trapezoidal pressure on both faces as block forces.
  void set_fluid_pressure(std::vector<double> point_pressure_Pa, std::vector<char> joint_wetted);

  // --- time stepping --------------------------------------------------------------
  /// Solves one step of length dt, with an optional coupled model; throws
  /// ConvergenceError (nothing committed, the coupled model aborted).
  StepStatistics step(double dt_s, StepCoupling* coupling = nullptr);

  // --- for coupled models, valid during a step ---------------------------------------
  /// Adds the block forces of a pressure varying linearly from pressure_p (at the
  /// joint's point p) to pressure_q, acting on both faces of the joint.
  void add_joint_pressure_load(int joint, double pressure_p_Pa, double pressure_q_Pa, Eigen::VectorXd& forces) const;
  JointEndGap joint_end_gap(int joint, int end) const;

  // --- state queries --------------------------------------------------------------
  const mesh::Mesh& mesh() const { return mesh_; }
  int n_blocks() const { return static_cast<int>(mesh_.blocks.size()); }
  const std::vector<Contact>& contacts() const { return contacts_; }
  /// Contacts of a joint: indices of its end at p and at q.
  std::array<int, 2> joint_contacts(int joint) const { return {2 * joint, 2 * joint + 1}; }
  /// Current corner position of a block.
  Vec2 corner(int block, int local) const { return corners_[corner_offset_[block] + local]; }
  int n_corners(int block) const { return corner_offset_[block + 1] - corner_offset_[block]; }
  Vec2 initial_corner(int block, int local) const { return initial_corners_[corner_offset_[block] + local]; }
  const Eigen::Vector3d& stress(int block) const { return stress_[block]; }
  const std::vector<int>& block_material() const { return block_material_; }
  /// Normal separation of the two faces of a joint at one end (mean of its springs) [m].
  double joint_gap(int joint, int end) const;
  /// Contact normal and shear force (tension positive) of a contact at the committed state [N].
  std::pair<double, double> contact_forces(int contact) const;
  /// Total displacement of a material point of block `block`, evaluated at its current position.
  const std::vector<Vec6>& last_step_displacement() const { return last_d_; }
  bool joint_wetted(int joint) const { return joint_wetted_[joint] != 0; }
  int total_vertex_vertex_activations() const { return total_vv_activations_; }
  const MechanicsSettings& settings() const { return settings_; }
  const std::vector<Material>& materials() const { return materials_; }

  /// The assembled matrix of the last open-close iteration (tests, benchmarks).
  const BlockSparseMatrix& stiffness() const { return stiffness_; }

 private:
  struct PointAttachment {   // a fixed point or point load attached to a block
    int block;
    Vec2 position;           // current position [m]
    Vec2 anchor;             // fixed points: where the point must stay [m]
    Vec2 force_N;
  };
  struct BoundaryStress {
    int boundary_edge;
    Eigen::Matrix2d stress_Pa;
  };

  void build_contacts();
  /// (Re)builds K's pattern from the joints and the active vertex-vertex contacts; a
  /// new symbolic analysis follows at the next factorisation.
  void rebuild_pattern();
  int block_containing(const Vec2& p) const;
  void update_block_geometry();
  void assemble_block_terms(double dt_s);
  void linearise_spring(VertexEdgeSpring& s) const;
  void linearise_contacts();
  void assemble_contacts();
  void add_spring_to_rhs(const VertexEdgeSpring& s, double weight, double force_normal, double force_shear,
                         bool normal, bool shear);
  Eigen::VectorXd solve_alm(StepStatistics& stats);
  double spring_gap(const VertexEdgeSpring& s, const Eigen::VectorXd& d) const;
  double spring_shear(const VertexEdgeSpring& s, const Eigen::VectorXd& d) const;
  int update_states(const Eigen::VectorXd& d, StepStatistics& stats);
  bool may_fail(const Contact& c) const;
  /// Blocks a and c are joined at the point by a chain of joint contacts that are
  /// closed in `joint_state` (one state per joint contact).
  bool joined_by_closed_joints(int point, int block_a, int block_c,
                               const std::vector<ContactState>& joint_state) const;
  /// Spring to activate if a corner of a vertex-vertex candidate penetrates deeper than
  /// the activation tolerance (seed 2.3 vi); std::nullopt otherwise.
  std::optional<VertexEdgeSpring> vertex_vertex_spring(const Contact& c, const Eigen::VectorXd& d,
                                                       double& max_penetration) const;
  void reset_shear_reference(VertexEdgeSpring& s, const Eigen::VectorXd& d) const;
  Vec2 displaced(int block, const Vec2& p, const Eigen::VectorXd& d) const;
  void commit(const Eigen::VectorXd& d, double dt_s);

  mesh::Mesh mesh_;
  std::vector<Material> materials_;
  MechanicsSettings settings_;

  // Block state (committed).
  std::vector<int> corner_offset_;
  std::vector<Vec2> corners_, initial_corners_;
  std::vector<int> block_material_;
  std::vector<Eigen::Vector3d> stress_;
  std::vector<Vec6> velocity_;
  std::vector<Vec6> last_d_;

  // Per-step block terms.
  std::vector<PolygonMoments> moments_;
  std::vector<Mat6> block_matrix_;
  Eigen::VectorXd load_vector_;

  // Loads and constraints.
  std::vector<PointAttachment> fixed_points_, point_loads_;
  std::vector<BoundaryStress> boundary_stresses_;
  Vec2 body_force_{0, 0};
  std::vector<double> point_pressure_;
  std::vector<char> joint_wetted_, point_pressurised_;
  StepCoupling* coupling_ = nullptr;  // during a coupled step

  // Contacts: 2 per joint (ends p, q) first, then vertex-vertex candidates.
  std::vector<Contact> contacts_;
  std::vector<int> contacts_at_point_offset_, contacts_at_point_;
  int total_vv_activations_ = 0;
  std::string last_change_;      // first state change of the last open-close check
  double gap_round_off_m_ = 0.0;  // gaps below this are round-off of the coordinates
  std::vector<int> flips_;
  std::vector<ContactState> next_joint_state_;  ///< update_states: joint states after this round
  std::vector<double> alm_corrections_, alm_previous_corrections_;  ///< solve_alm: k g, k s per contact
  std::vector<std::pair<int, int>> couplings_;  // block pairs in K's pattern
  bool pattern_changed_ = false;  // state changes of each contact within the current step

  BlockSparseMatrix stiffness_;
  SpdSolver solver_;
};

}  // namespace hfdda::dda
