#pragma once
// In-memory form of a YAML case file. Every parameter of the seed's tables can be
// written; units are SI and appear in the field names. Defaults below are the
// documented defaults (docs/case_file.md lists them with their allowed ranges).
//
// The keys the seed draws from distributions in its Monte Carlo runs (section 5.5) may be
// given one instead of a number: the law is then kept in the member `<name>_law` beside
// the number, which holds the law's central value until the model draws it (once per
// run, block by block or joint by joint; docs/distributions.md).

#include <optional>
#include <string>
#include <vector>

#include "core/geometry.hpp"
#include "mesh/mesh.hpp"
#include "stochastic/scalar_distribution.hpp"

namespace hfdda::io {

/// The distribution a key was given instead of a number (none: the number holds).
using ParameterLaw = std::optional<stochastic::ScalarDistribution>;

struct DomainConfig {
  Rect outer{-50, 50, -50, 50};
  std::optional<Rect> inner;  ///< finer, separately meshed inner domain (seed 3.1-3.5)
};

enum class MeshKind { structured, delaunay };

struct MeshConfig {
  MeshKind kind = MeshKind::structured;
  // structured
  double cell_size_m = 1.0;
  double outer_growth = 1.2;
  mesh::CellSplit split = mesh::CellSplit::two;
  // delaunay
  double max_area_inner_m2 = 1.0;
  double max_area_outer_m2 = 10.0;
  double min_angle_deg = 25.0;
  double snap_tolerance_m = 0.0;  ///< feature ends this near another feature meet it (0: rounding only)
  int line = 0;  ///< case-file line of the `mesh` section, for mesh errors
};

/// An elastic material and where it applies: "all", "inner", "outer" or "box".
/// Zones are applied in order, later zones override earlier ones (by block centroid).
struct MaterialConfig {
  std::string name = "rock";
  std::string region = "all";
  Rect box;
  double youngs_modulus_Pa = 25.0e9;  // seed Table 3.1
  double poissons_ratio = 0.25;
  double density_kg_m3 = 2650.0;
  ParameterLaw youngs_modulus_law, poissons_ratio_law;  ///< drawn block by block (seed 5.5)
  int line = 0;  ///< case-file line of the list item
};

/// Defaults of every joint; fractures may override them.
struct JointConfig {
  double tensile_strength_Pa = 0.0;
  /// K_IC; set, each joint's T0 is K_IC / sqrt(pi L / 2) from its length L (seed eq. 4.13)
  std::optional<double> fracture_toughness_Pa_sqrt_m;
  double cohesion_Pa = 0.0;
  double friction_angle_deg = 30.0;
  /// Hydraulic width w0 [m] a closed joint keeps for flow (0: intact rock, no flow until it opens).
  double hydraulic_width_m = 0.0;
  /// Drawn joint by joint (seed 5.5), on the joints no fracture overrides.
  ParameterLaw tensile_strength_law, friction_angle_law, hydraulic_width_law;
  bool breakable = true;
  /// "all" or "inner": only joints between two blocks of domain.inner may break
  /// (fracture overrides still apply).
  std::string breakable_region = "all";
};

/// Initial aperture of a fluid-filled fracture (fractures[].initial_opening).
enum class InitialOpening { width, elastic };

/// A line feature: initial fracture, natural fracture, prescribed path or interface.
/// Joints lying on it take its overrides.
struct FractureConfig {
  std::string name;
  Vec2 from{0, 0}, to{0, 0};
  double segment_length_m = 0.0;     ///< Delaunay constraint piece length (0: mesh size)
  bool initially_open = false;
  bool natural = false;
  std::optional<bool> breakable;
  std::optional<double> tensile_strength_Pa;
  std::optional<double> fracture_toughness_Pa_sqrt_m;  ///< K_IC; the item's own T0 or K_IC wins over `joints`
  std::optional<double> cohesion_Pa;
  std::optional<double> friction_angle_deg;
  /// Hydraulic width w0 of its joints while mechanically closed (seed Table 5.1: 1 um for
  /// natural fractures): fluid invades them through it; unset: joints.hydraulic_width.
  std::optional<double> hydraulic_width_m;
  /// Drawn joint by joint over its joints (seed 5.5).
  ParameterLaw tensile_strength_law, friction_angle_law, hydraulic_width_law;
  std::optional<double> pressure_Pa;  ///< prescribed fluid pressure on its joints
  /// Initially open joints that start filled with fluid (at zero pressure) and join the
  /// flow network from t = 0 (seed 3.2: the joints at the injection point).
  bool fluid_filled = false;
  double initial_width_m = 0.0;       ///< initial aperture of fluid-filled joints (0: the minimum width)
  /// Where the initial aperture of fluid-filled joints comes from: initial_width, or the
  /// rock's opening under initial_pressure (coupling/initial_opening.hpp).
  InitialOpening initial_opening = InitialOpening::width;
  double initial_pressure_Pa = 0.0;   ///< initial fluid pressure of fluid-filled joints
  /// Rows of a fracture map that reached past domain.outer: the length cut off there [m].
  double clipped_length_m = 0.0;
  int line = 0;                       ///< case-file line, for error messages
};

/// Which joints of a structured mesh may break, said once instead of one fracture per
/// grid line (seed 3.4, 3.5: only the inner domain fractures; along the grid lines, the
/// cell diagonals or both; weaker -45 degree diagonals). The pattern is a square grid of
/// side `cell_size_m` with a grid point at `origin`: its horizontal and vertical lines
/// and the diagonals of its cells, each clipped to `region` (lines on the edges of
/// `region` excluded). The loader turns every line into a FractureConfig appended to
/// CaseConfig::fractures, leaving out the parts that lie on a written fracture.
struct BreakablePatternConfig {
  std::string name = "pattern";
  Rect region;
  double cell_size_m = 1.0;
  Vec2 origin{0, 0};
  /// Families of lines, expanded in this order: "horizontal", "vertical", "plus_45"
  /// (y = x + c) and "minus_45" (y = -x + c).
  std::vector<std::string> lines;
  bool breakable = true;
  std::optional<double> tensile_strength_Pa;  ///< unset: joints.tensile_strength
  std::optional<double> fracture_toughness_Pa_sqrt_m;  ///< K_IC; unset: joints.fracture_toughness
  std::optional<double> cohesion_Pa;          ///< unset: joints.cohesion
  std::optional<double> friction_angle_deg;   ///< unset: joints.friction_angle
  int line = 0;                               ///< case-file line, for error messages
};

/// A map of natural fractures as line segments in a CSV file (outcrops, image logs,
/// other DFN tools): header x1,y1,x2,y2 and optional columns set, tensile_strength,
/// cohesion, friction_angle, hydraulic_width. The loader turns every row into a
/// FractureConfig appended to CaseConfig::fractures (io/fracture_maps.hpp).
struct FractureMapConfig {
  std::string name = "map";
  std::string file;                  ///< as written
  std::string path;                  ///< resolved against the case file that names it
  bool natural = true;
  double segment_length_m = 0.0;     ///< Delaunay constraint piece length (0: mesh size)
  std::optional<bool> breakable;
  std::optional<double> tensile_strength_Pa, cohesion_Pa, friction_angle_deg, hydraulic_width_m;
  int line = 0;
};

/// Distribution of the target lengths of a fracture set's fractures [m]: `uniform` (min,
/// max), `triangular` (min, mode, max), `lognormal` (median, sigma: ln L ~ N(ln median,
/// sigma^2)) or `power_law` (exponent a, min, max: density ~ L^-a on [min, max]). Only the
/// keys of the chosen distribution are given (checked when the set is read).
struct FractureLengthConfig {
  std::string distribution = "uniform";
  std::optional<double> min_m, max_m, mode_m, median_m, sigma, exponent;
};

/// A stochastic set of natural fractures grown along the joints of the Delaunay mesh
/// (seed 5.3; solver/networks/fracture_network_generator.hpp): candidates are the joints
/// within `azimuth_tolerance_deg` of the azimuth, a fraction of them are seeds, each grown
/// joint by joint to a length drawn from `length`. The azimuth is measured in degrees
/// clockwise from the domain's +y axis (0: along y, 90: along x, 45: south-west to
/// north-east). Its fractures are natural, named "<name>.<k>", and take the values below
/// (unset: those of `joints`).
struct FractureSetConfig {
  std::string name;
  double azimuth_deg = 0.0;
  double azimuth_tolerance_deg = 5.0;   ///< seed 5.3: +- 5 degrees
  double growth_tolerance_deg = 45.0;   ///< largest deviation of a joint added while growing (90: any that advances)
  double seed_fraction = 0.12;          ///< seed 5.3: 12 % of the candidates
  FractureLengthConfig length;
  std::optional<double> tensile_strength_Pa, cohesion_Pa, friction_angle_deg, hydraulic_width_m;
  /// Drawn joint by joint over the joints of its fractures (seed 5.5, Tables 5.5, 5.6).
  ParameterLaw tensile_strength_law, friction_angle_law, hydraulic_width_law;
  int line = 0;
};

/// Fracturing fluid (seed 2.1, Table 3.1). Present in a case file means the flow
/// network is solved, coupled with the blocks.
struct FluidConfig {
  double density_kg_m3 = 1000.0;        ///< reference density rho0 (eq. 2.6)
  double bulk_modulus_Pa = 2.2e9;       ///< Kf; compressibility c_f = 1 / Kf
  double viscosity_Pa_s = 1.0e-3;       ///< mu (cubic law, eq. 2.2)
  ParameterLaw viscosity_law;           ///< drawn once per run (seed 5.5)
  double reference_pressure_Pa = 0.0;   ///< p0 of eq. 2.6
  /// Carter coefficient C_L of each wall [m/s^0.5]; both walls leak (erratum 4 in docs/seed_errata.md).
  double leak_off_coefficient_m_sqrt_s = 0.0;
  /// "sealed", or "vented": where a joint holding fluid meets the boundary of
  /// domain.inner (the edge of a laboratory block), the fluid is at zero pressure and
  /// what reaches it leaves the model (FlowNetwork::set_vents).
  std::string edge = "sealed";
};

/// A fluid source at the mesh point nearest `at` (seed 3.2: Q0 at the origin).
struct InjectionConfig {
  std::string name = "injection";
  Vec2 at{0, 0};
  double mass_rate_kg_s = 0.0;          ///< per metre of out-of-plane thickness
  ParameterLaw mass_rate_law;           ///< drawn once per run (seed 5.5)
  double start_time_s = 0.0;
  /// Injection stops once this mass per metre has gone in (seed 5.5: 60 kg); the run goes
  /// on shut in. Absent: no limit.
  std::optional<double> mass_limit_kg;
  /// Compliance of the pump, lines and borehole upstream of the fracture (fluid::Injection)
  /// [m^2/Pa per metre of out-of-plane thickness]; 0: stiff.
  double system_compliance_m2_Pa = 0.0;
  int line = 0;
};

/// A named gauge: pressure and aperture at the mesh point nearest `at`, every step.
struct ProbeConfig {
  std::string name;
  Vec2 at{0, 0};
  int line = 0;
};

/// Far-field stress (tension positive) applied as tractions t = sigma . n on the
/// listed sides of the outer boundary (the seed applies it on top and bottom).
struct FarFieldConfig {
  double sxx_Pa = 0.0, syy_Pa = 0.0, sxy_Pa = 0.0;
  ParameterLaw sxx_law, syy_law, sxy_law;  ///< drawn once per run (seed 5.6)
  std::vector<std::string> sides{"top", "bottom"};  ///< subset of left/right/bottom/top
  /// true: the rock starts in equilibrium with the stress (initial block stresses and
  /// joint contact forces, the traction on all four sides); no loading transient and no
  /// load carried by fixed points. false: the seed's loading by boundary forces alone.
  bool in_situ = false;
};

/// Quasi-static load ramp (seed 4.2-4.4): far-field tractions t = s (sigma_unit . n) on
/// the listed sides, with the magnitude s raised level by level, one static step per
/// level, the failure rules of seed 2.3 applied at every level. Levels are either a
/// uniform ramp (start, increment, maximum) or a piecewise-linear history s(t) sampled
/// every time.dt. The run ends at the stop condition or the last level.
struct LoadRampConfig {
  /// Far-field stress per unit of the ramped magnitude s (dimensionless, tension positive).
  double sxx = 0.0, syy = 0.0, sxy = 0.0;
  std::vector<std::string> sides{"top", "bottom"};  ///< subset of left/right/bottom/top
  std::optional<double> start_Pa;      ///< s of the first level (uniform ramp; default 0)
  std::optional<double> increment_Pa;  ///< s between levels (uniform ramp)
  std::optional<double> maximum_Pa;    ///< largest s (uniform ramp)
  std::vector<Vec2> history;           ///< (t [s], s [Pa]) points, t increasing (instead of the ramp)
  /// Uniform ramp: from two levels without a failure, predict the next failure from the
  /// linear response and jump to just below it, instead of climbing there level by level.
  bool predict_failures = true;
  /// "none", "broken_fraction" (the broken length of `stop_joints` exceeds
  /// `stop_fraction` of their length) or "failed_both_sides" (a joint away from the
  /// crack has failed on both sides of `crack_centre` along `crack_direction`).
  std::string stop_when = "none";
  std::vector<std::string> stop_joints;  ///< names of fractures or breakable patterns
  double stop_fraction = 0.75;
  Vec2 crack_centre{0, 0};
  Vec2 crack_direction{1, 0};
  int line = 0;
};

struct PointLoadConfig {
  Vec2 at{0, 0};
  Vec2 force_N_per_m{0, 0};  ///< per metre of out-of-plane thickness
  int line = 0;
};

struct FixedPointConfig {
  Vec2 at{0, 0};
  int line = 0;
};

enum class ContactMethod { penalty, augmented_lagrangian };

struct ContactConfig {
  ContactMethod method = ContactMethod::augmented_lagrangian;
  double normal_stiffness_factor = 100.0;  ///< k_n = factor * max E  (seed Table 3.1)
  double shear_stiffness_factor = 100.0;   ///< k_s = factor * max E
  double vertex_vertex_activation_m = 1.0e-6;  ///< seed 2.3 (vi)
  double fixed_point_stiffness_factor = 100.0;  ///< fixed-point penalty = factor * max E
  /// ALM on intact joint contacts only, penalty on broken ones (seed 5.1); see docs/case_file.md.
  bool two_tier = false;
  /// With two_tier: intact contacts' springs / the penalty springs (docs/case_file.md).
  double intact_stiffness_ratio = 100.0;
};

enum class AnalysisKind { static_analysis, dynamic_analysis };
/// How an open-close cycle is resolved (numerics.cycle_resolution).
enum class CycleResolution { most_open, close_penetrating };
/// How the flow Newton's linear systems are solved (coupling::FlowJacobian).
enum class FlowJacobianKind { dense, krylov, augmented, automatic };
/// Which response of the apertures to the pressures the flow solve uses
/// (dda::MechanicsSettings::converged_response_stiffening).
enum class ApertureResponse { fixed_multipliers, converged_contacts };
/// How the fluid pressure on a joint's faces loads the blocks (dda::MechanicsSettings::lumped_fluid_load).
enum class FluidLoad { integrated, lumped };

struct NumericsConfig {
  AnalysisKind analysis = AnalysisKind::static_analysis;  ///< static: velocities reset each step
  /// Static analysis: blocks the contact state leaves a rigid motion take the inertia of
  /// this time instead of the step's (docs/design_notes.md section 25) [s].
  double mechanism_inertia_time_s = 0.1;
  /// Contact-state changes within a step applied to K's factorisation as a low-rank
  /// correction (docs/design_notes.md section 26).
  bool low_rank_updates = false;
  double alm_force_tolerance = 1.0e-7;  ///< ALM stop: max |k g| <= tol * max |contact force|
  int max_alm_iterations = 200;
  int max_open_close_iterations = 200;
  /// Cycle detection (seed 5.1): a contact changing state more often than this in a step
  /// is set to its most open state of the step and held there.
  int max_state_flips = 6;
  /// Cycle resolution: the most open state (seed 5.1), or closed where held open the faces
  /// would pass through each other (dda::MechanicsSettings::close_penetrating_cycles).
  CycleResolution cycle_resolution = CycleResolution::most_open;
  /// A contact whose bond broke in this step may be re-locked by a slip reversal within
  /// the step (dda::MechanicsSettings::relock_in_failure_step).
  bool relock_in_failure_step = true;
  /// Friction of held (penalty, two-tier unbonded) contacts at the normal force of the
  /// solution, and their re-locking on the step's slip (dda::MechanicsSettings::friction_at_solution).
  bool friction_at_solution = false;
  /// Bonds fail only in a round in which no contact changes state
  /// (fracture::FractureRules::failures_on_settled_contacts).
  bool failures_on_settled_contacts = false;
  double tie_tolerance = 1.0e-3;        ///< seed 2.3 (iii): failures within 0.1 % split
  bool shear_failure_of_intact_joints = false;  ///< false: seed 2.3 (ii), tension first
  // Coupled hydro-mechanical step (seed 2.1, 2.4; docs/formulation.md section 4).
  double min_width_main_m = 0.5e-6;     ///< minimum aperture once wetted, network interior
  double min_width_tip_m = 0.1e-6;      ///< minimum aperture at fracture tips
  double max_closing_fraction = 0.05;   ///< an aperture may close by at most this per step
  double coupling_tolerance = 1.0e-9;   ///< relative pressure change and mass residual (erratum 2)
  int max_coupling_iterations = 60;     ///< Newton iterations on the pressures per solve
  FlowJacobianKind flow_jacobian = FlowJacobianKind::automatic;  ///< dense S, S as an operator, or by size
  /// Krylov path: GMRES may stop early while the flow Newton converges well
  /// (fluid::FlowSettings::inexact_linear_solves).
  bool inexact_flow_solves = true;
  ApertureResponse aperture_response = ApertureResponse::fixed_multipliers;
  FluidLoad fluid_load = FluidLoad::integrated;
  int max_step_cuts = 4;                ///< a failed step is retried with dt halved this often
};

/// Which rule fails an intact joint (`fracture.criterion`).
enum class FailureCriterionKind { strength, energy_release_rate };

/// How intact joints fail: the seed's strength rule everywhere (seed 2.3), or, at crack
/// tips, a toughness criterion on the energy release rates computed from the solution by
/// virtual crack closure (docs/formulation.md section 5), the strength rule elsewhere.
/// How the toughness criterion reads G from the crack closure (`fracture.crack_closure`).
enum class CrackClosureKind { one_joint, extrapolated };

struct FractureCriterionConfig {
  FailureCriterionKind criterion = FailureCriterionKind::strength;
  CrackClosureKind crack_closure = CrackClosureKind::extrapolated;
  std::optional<double> fracture_toughness_Pa_sqrt_m;  ///< K_IC; required with energy_release_rate
  std::optional<double> mode2_toughness_Pa_sqrt_m;     ///< K_IIC; unset: K_IC
};

struct TimeConfig {
  double dt_s = 1.0;
  double end_time_s = 1.0;
  /// "none", or "fluid_at_edge": the run ends after the first step in which a joint
  /// holding fluid touches the boundary of domain.inner (a laboratory block: the fluid escapes).
  std::string stop_when = "none";
};

struct OutputConfig {
  int every_steps = 1;  ///< joint CSV and VTU every n steps (and always at the end); 0: end only
  bool vtu = true;
};

/// A Monte Carlo ensemble of the case (`hfdda ensemble`; seed 5.5, 5.6): how many
/// realisations, the master seed of their random streams, which groups of parameters are
/// drawn anew for each realisation (the others are drawn once and held), and the maps.
struct EnsembleConfig {
  int realisations = 10;
  int master_seed = 1;
  /// Groups drawn anew per realisation: network (fracture_sets), rock (materials, joints,
  /// far_field), natural_fractures (fractures, fracture_sets properties), fluid (fluid,
  /// injections). A group not listed is drawn once from the master seed and held.
  std::vector<std::string> resample{"network", "rock", "natural_fractures", "fluid"};
  double map_every_s = 900.0;   ///< likelihood maps every this much simulated time (seed: 15 min)
  double grid_cell_m = 10.0;    ///< side of the grid-map cells (seed Figures 5.24-5.44: 10 m)
};

struct CaseConfig {
  std::string file;   ///< path of the (top) case file
  std::string mesh_file;  ///< file that set the `mesh` section (the top file or a base it extends)
  /// Every file of the `extends` chain, name and text, in the order read: what the case
  /// is made of (an ensemble's fingerprint; a base file edited changes it).
  std::string source_text;
  std::string title;
  DomainConfig domain;
  MeshConfig mesh;
  std::vector<MaterialConfig> materials{MaterialConfig{}};
  JointConfig joints;
  /// The written line features, then the lines of breakable_patterns (added by the loader).
  std::vector<FractureConfig> fractures;
  std::vector<BreakablePatternConfig> breakable_patterns;
  /// Natural-fracture maps read from CSV files (their rows end up in `fractures`).
  std::vector<FractureMapConfig> fracture_maps;
  /// Stochastic natural-fracture sets generated on the mesh (seed 5.3), and the seed of
  /// their random numbers: the same seed gives the same network on every machine.
  std::vector<FractureSetConfig> fracture_sets;
  int network_seed = 0;
  /// Seed of the draws of the keys given as distributions (docs/distributions.md): the
  /// same seed gives the same values on every machine. It does not change the network.
  int random_seed = 1;
  FarFieldConfig far_field;
  std::optional<LoadRampConfig> load_ramp;  ///< absent: loads constant, time stepping to end_time
  std::vector<PointLoadConfig> point_loads;
  Vec2 body_force_N_m3{0, 0};
  std::vector<FixedPointConfig> fixed_points;
  ContactConfig contact;
  std::optional<FluidConfig> fluid;     ///< absent: no flow network (prescribed pressures only)
  std::vector<InjectionConfig> injections;
  std::vector<ProbeConfig> probes;
  NumericsConfig numerics;
  FractureCriterionConfig fracture;
  TimeConfig time;
  OutputConfig output;
  std::optional<EnsembleConfig> ensemble;  ///< read by `hfdda ensemble` only
};

/// Whether any key of the case is given as a distribution.
bool has_distributions(const CaseConfig& config);

/// Reads and validates a case file (and the file named by its `extends:` key, whose
/// values it overrides). Throws InputError naming file, line, key and rule on an
/// unknown key, a wrong type or an out-of-range value; nothing is written.
CaseConfig load_case_file(const std::string& path);

/// Same, from YAML text (`file_label` is used in error messages).
CaseConfig load_case_text(const std::string& yaml_text, const std::string& file_label);

/// The key reference (Markdown) that docs/case_file.md holds, generated from the key
/// tables that drive parsing and validation, so the two cannot drift.
std::string case_file_reference_markdown();

}  // namespace hfdda::io
