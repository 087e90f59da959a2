#pragma once
// Stochastic natural-fracture networks grown along the joints of a Delaunay mesh
// (W. E. Morgan, PhD dissertation, Georgia Institute of Technology, 2014, section 5.3).
//
// Per fracture set: the joints whose direction lies within a tolerance of the set's
// azimuth are the candidates; each candidate is drawn as a seed with probability
// `seed_fraction`; each seed gets a length drawn from the set's distribution and grows,
// joint by joint, at both ends onto the neighbouring joint closest to the azimuth until
// it reaches that length or can go no further. Fractures are made of whole mesh joints,
// so they are never shorter than a joint and meet other fractures exactly at mesh points
// (the point of the seed's method: no slivers of tiny blocks between near-misses).
//
// Conventions (docs/design_notes.md, "Fracture-network generator"):
//   - azimuth: degrees clockwise from the domain's +y axis (a compass bearing with y
//     north, x east): 0 runs along y, 90 along x, 45 from south-west to north-east. A
//     fracture is a line, so azimuths are taken modulo 180.
//   - length of a fracture: the sum of the lengths of its joints (the path along the
//     mesh, slightly longer than the straight distance between its ends).
//   - random numbers: GSL's mt19937, one generator per set seeded from the network seed
//     and the set's name, so a network is the same on every machine, and adding, removing
//     or reordering sets leaves the draws (seeds, target lengths) of the others unchanged.
//     The lengths are drawn by the samplers of stochastic/scalar_distribution.hpp.
//
// Pure: no I/O, no global state; the same mesh, settings and seed give the same network.

#include <cstdint>
#include <string>
#include <vector>

#include "mesh/mesh.hpp"

namespace hfdda::networks {

enum class LengthDistribution { uniform, triangular, lognormal, power_law };

/// The distribution of the target lengths of a set's fractures [m].
struct LengthLaw {
  LengthDistribution distribution = LengthDistribution::uniform;
  double min_m = 0.0;     ///< uniform, triangular, power_law: smallest length
  double max_m = 0.0;     ///< uniform, triangular, power_law: largest length
  double mode_m = 0.0;    ///< triangular: most likely length, in [min, max]
  double median_m = 0.0;  ///< lognormal: median exp(mu), so ln L ~ N(ln median, sigma^2)
  double sigma = 0.0;     ///< lognormal: standard deviation of ln L [-]
  double exponent = 0.0;  ///< power_law: a of the density p(L) ~ L^-a on [min, max] [-]
};

/// Cumulative distribution P(L <= length) of a length law (the reference of the tests).
double length_cdf(const LengthLaw& law, double length_m);

/// The settings of one fracture set.
struct FractureSetSettings {
  std::string name;
  double azimuth_deg = 0.0;              ///< clockwise from +y; [0, 180)
  double azimuth_tolerance_deg = 5.0;    ///< candidates and seeds: within +- this of the azimuth; (0, 90)
  /// Growth: the joint a fracture grows onto may deviate at most this from the azimuth;
  /// (0, 90]. 90: any joint that advances along the azimuth, the seed's rule as written;
  /// the default, 45, differs from it only where the closest joint is nearly across the
  /// set (1.5 % of the growth steps of the seed's network over five seeds).
  double growth_tolerance_deg = 45.0;
  double seed_fraction = 0.12;           ///< probability that a candidate is a seed; (0, 1]
  LengthLaw length;
};

/// One generated fracture.
struct GeneratedFracture {
  int set = -1;                ///< index into the settings
  std::string name;            ///< "<set name>.<k>", k = 1, 2, ... within the set
  std::vector<int> joints;     ///< mesh joint ids, in order from one end to the other
  int seed_joint = -1;
  double target_length_m = 0.0;
  double length_m = 0.0;       ///< sum of its joints' lengths
  /// It stopped because the next joint would have taken it further from its target length;
  /// false: both ends were blocked before (no continuation within the growth tolerance, the
  /// domain's edge, or another fracture in the way).
  bool reached_target = false;
};

/// A seed drawn for a set: its joint and target length, and the fracture grown from it.
struct SeedDraw {
  int joint = -1;
  double target_length_m = 0.0;
  int fracture = -1;  ///< index into FractureNetwork::fractures; -1: the joint already belonged to a fracture
};

struct SetStatistics {
  int candidates = 0;          ///< joints within azimuth_tolerance of the azimuth (not reserved)
  int seeds = 0;               ///< candidates drawn as seeds
  int absorbed_seeds = 0;      ///< seeds on a joint an earlier fracture had already taken
  int fractures = 0;
  int fractures_reaching_target = 0;
  int joints = 0;
  double total_length_m = 0.0;
  std::vector<SeedDraw> seed_draws;  ///< every seed, in joint-id order
};

struct FractureNetwork {
  std::vector<GeneratedFracture> fractures;  ///< set after set, seeds in joint-id order
  std::vector<SetStatistics> sets;           ///< one per set
  std::vector<int> fracture_of_joint;        ///< per mesh joint: index into fractures, -1 none
};

/// Checks one set's settings; throws ModelError "<key>: <rule> (got ...)" naming the
/// case-file key below `key_prefix` (e.g. "fracture_sets[0]") and the rule broken.
void validate_settings(const FractureSetSettings& set, const std::string& key_prefix);

/// Generates the network of `sets` on `mesh`. `reserved` (empty, or one flag per joint):
/// joints that no generated fracture may take (the case's own fractures); a fracture
/// growing into one stops there. A joint belongs to at most one generated fracture: sets
/// are generated in order, seeds in joint-id order, and a fracture that grows into an
/// earlier one stops at it. Throws ModelError on invalid settings (validate_settings).
FractureNetwork generate_fracture_network(const mesh::Mesh& mesh, const std::vector<FractureSetSettings>& sets,
                                          std::uint64_t seed, const std::vector<char>& reserved = {});

/// Azimuth of a joint's line, degrees clockwise from +y, in [0, 180).
double joint_azimuth_deg(const mesh::Mesh& mesh, int joint);

/// Angle between two lines given by their azimuths [deg], in [0, 90].
double azimuth_difference_deg(double a_deg, double b_deg);

/// The seed of the GSL generator of the set named `set_name` for network seed `seed`
/// (stochastic::stream_seed).
unsigned long set_generator_seed(std::uint64_t seed, const std::string& set_name);

}  // namespace hfdda::networks
