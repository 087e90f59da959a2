#include "io/fracture_sets.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "io/case_fields.hpp"
#include "io/sampled_fields.hpp"

namespace hfdda::io {

using namespace schema;

namespace {

/// The keys each length distribution takes, in the order they are named in messages.
const std::map<std::string, std::vector<std::string>>& distribution_keys() {
  static const std::map<std::string, std::vector<std::string>> keys{
      {"uniform", {"min", "max"}},
      {"triangular", {"min", "mode", "max"}},
      {"lognormal", {"median", "sigma"}},
      {"power_law", {"exponent", "min", "max"}}};
  return keys;
}

/// Exactly the keys of the chosen distribution, min <= max and min <= mode <= max.
void check_length(const FileReader& r, const YAML::Node& map, const std::string& key, const FractureLengthConfig& l,
                  const std::set<std::string>& seen) {
  const std::vector<std::string>& wanted = distribution_keys().at(l.distribution);
  const std::string takes = "distribution " + l.distribution + " takes " + join(wanted, ", ");
  for (const std::string& name : seen)
    if (name != "distribution" && std::find(wanted.begin(), wanted.end(), name) == wanted.end())
      r.fail(map[name], child_key(key, name), "is not used by " + takes);
  for (const std::string& name : wanted)
    if (!seen.contains(name)) r.fail(map, child_key(key, name), "is required: " + takes);
  if (l.min_m && l.max_m && *l.max_m < *l.min_m)
    r.fail(map["max"], child_key(key, "max"),
           "must be >= min (got min " + format_number(*l.min_m) + ", max " + format_number(*l.max_m) + ")");
  if (l.mode_m && !(*l.mode_m >= *l.min_m && *l.mode_m <= *l.max_m))
    r.fail(map["mode"], child_key(key, "mode"),
           "must be in [min, max] (got min " + format_number(*l.min_m) + ", mode " + format_number(*l.mode_m) +
               ", max " + format_number(*l.max_m) + ")");
}

const Table<FractureLengthConfig>& length_table() {
  using L = FractureLengthConfig;
  static const Table<L> table{
      "`fracture_sets[].length`",
      "The distribution of the lengths the set's fractures are grown to (each fracture's length is the sum of "
      "its joints' lengths), with exactly the keys of that distribution: `uniform` takes `min`, `max`; "
      "`triangular` `min`, `mode`, `max`; `lognormal` `median`, `sigma` (ln L is normal with mean ln(median) "
      "and standard deviation sigma); `power_law` `exponent`, `min`, `max` (density proportional to "
      "L^-exponent between min and max). min <= mode <= max.",
      {choice({"distribution", "", "§5.3: uniform, \"though any distribution may be assigned\"",
               "the law of the target lengths"},
              &L::distribution,
              Choices<std::string>{{"uniform", "uniform"},
                                   {"triangular", "triangular"},
                                   {"lognormal", "lognormal"},
                                   {"power_law", "power_law"}}),
       optional_number({"min", "m", "§5.3: 20 m (Figure 5.8: 10 m)", "shortest length"}, &L::min_m,
                       positive_up_to(kMaxCoordinate), "none"),
       optional_number({"max", "m", "§5.3: 40 m (Figure 5.8: 20 m)", "longest length"}, &L::max_m,
                       positive_up_to(kMaxCoordinate), "none"),
       optional_number({"mode", "m", "", "triangular: the most likely length"}, &L::mode_m,
                       positive_up_to(kMaxCoordinate), "none"),
       optional_number({"median", "m", "", "lognormal: the median length exp(mu)"}, &L::median_m,
                       positive_up_to(kMaxCoordinate), "none"),
       optional_number({"sigma", "-", "", "lognormal: standard deviation of ln L"}, &L::sigma,
                       interval(0, true, 10, false), "none"),
       optional_number({"exponent", "-", "", "power_law: a of the density L^-a"}, &L::exponent,
                       interval(0, false, 10, false), "none")}};
  return table;
}

const Table<FractureSetConfig>& set_table() {
  using S = FractureSetConfig;
  static const Table<S> table{
      "`fracture_sets[]` items",
      "A stochastic set of natural fractures grown along the joints of the Delaunay mesh (seed 5.3): the joints "
      "within `azimuth_tolerance` of `azimuth` are the candidates; each is drawn as a seed with probability "
      "`seed_fraction`; each seed gets a length from `length` and grows joint by joint at both ends, onto the "
      "joint at its end that runs closest to the azimuth (if within `growth_tolerance`), until the next joint "
      "would take it further from its length than it is, or it meets the domain's edge, another fracture or a "
      "joint of `fractures`. Azimuths are degrees clockwise from the domain's +y axis: 0 runs along y, 90 "
      "along x, 45 from south-west to north-east. The fractures are natural, named `<name>.<k>` (k = 1, 2, "
      "...), and take the values below (unset: those of `joints`). A joint belongs to one fracture at most: "
      "sets are grown in order, and a fracture of `fractures` keeps its joints. Random numbers: GSL's mt19937, "
      "one generator per set seeded from `network_seed` and the set's name, so the same case gives the same "
      "network on every machine, and adding or reordering sets leaves the seeds and lengths drawn for the "
      "others unchanged. `hfdda network CASE --out DIR` writes the network without running the case.",
      {required(identifier({"name", "", "§5.4: J1, J2", "set name; its fractures are <name>.<k>"}, &S::name)),
       required(number({"azimuth", "deg", "§5.3: 45 and 135 deg; 0 and 90 deg",
                        "direction of the set, clockwise from the +y axis"},
                       &S::azimuth_deg, interval(0, false, 180, true))),
       number({"azimuth_tolerance", "deg", "§5.3: +- 5 deg",
               "candidates (and seeds) are the joints within +- this of the azimuth"},
              &S::azimuth_tolerance_deg, interval(0, true, 90, true)),
       number({"growth_tolerance", "deg", "§5.3: the adjacent joint closest to the azimuth",
               "a fracture grows onto the joint at its end closest to the azimuth only if that joint is within "
               "this of it; 90: any joint that advances along the azimuth (the seed's rule as written, which "
               "lets a fracture turn almost across its set where the mesh offers nothing closer)"},
              &S::growth_tolerance_deg, interval(0, true, 90, false)),
       required(number({"seed_fraction", "-", "§5.3: 12 % (Figure 5.9: 6 %); §5.4: 20 %, 15 %",
                        "probability that a candidate joint is a seed"},
                       &S::seed_fraction, interval(0, true, 1, false))),
       required(section({"length", "", "§5.3: uniform, 20 to 40 m", "distribution of the fracture lengths"},
                        &S::length, &length_table, check_length)),
       optional_sampled_number({"tensile_strength", "Pa", "Table 5.3: natural fracture T0 = 0; Tables 5.5, 5.6: "
                                "triangular on log10",
                                "tensile strength T0 of its bonds"},
                               &S::tensile_strength_Pa, &S::tensile_strength_law, zero_to(kMaxStrength),
                               "joints.tensile_strength", SamplingScope::joint),
       optional_number({"cohesion", "Pa", "Table 5.3: natural fracture C0 = 0", "cohesion C0 of its bonds"},
                       &S::cohesion_Pa, zero_to(kMaxStrength), "joints.cohesion"),
       optional_sampled_number({"friction_angle", "deg",
                                "Table 5.3: natural fracture phi = 35 deg; Tables 5.5, 5.6: triangular, 25 to 35 deg",
                                "friction angle of its joints"},
                               &S::friction_angle_deg, &S::friction_angle_law, interval(0, false, 90, true),
                               "joints.friction_angle", SamplingScope::joint),
       optional_sampled_number({"hydraulic_width", "m",
                                "Table 5.3: natural fracture w0 = 100 um; Tables 5.5, 5.6: triangular on log10, "
                                "80 to 200 um",
                                "w0 of its joints: fluid invades them through this width while they are closed"},
                               &S::hydraulic_width_m, &S::hydraulic_width_law, zero_to(kMaxHydraulicWidth),
                               "joints.hydraulic_width", SamplingScope::joint)}};
  return table;
}

}  // namespace

Field<CaseConfig> fracture_sets_key() {
  return map_list({"fracture_sets", "", "§5.3-5.4: fracture sets of a Delaunay mesh",
                   "stochastic natural-fracture sets grown along the mesh joints"},
                  &CaseConfig::fracture_sets, &set_table, 0, "none");
}

Field<CaseConfig> network_seed_key() {
  return integer({"network_seed", "", "§5.3: Figures 5.6 and 5.7 differ by their seed",
                  "seed of the random numbers of fracture_sets: the same seed gives the same network"},
                 &CaseConfig::network_seed, interval(0, false, 2147483647, false), "only with fracture_sets");
}

void check_fracture_sets(const CaseConfig& c, const MergedChecker& m) {
  if (c.fracture_sets.empty()) {
    if (m.present("network_seed")) m.fail("network_seed", "is only used with fracture_sets (there is none)");
    return;
  }
  if (c.mesh.kind != MeshKind::delaunay)
    m.fail("fracture_sets", "needs mesh.type: delaunay (the sets are grown along the joints of a Delaunay "
                            "triangulation, seed 5.3); the mesh is structured");
  const Rect& d = c.domain.outer;
  const double diagonal = std::hypot(d.width(), d.height());
  for (std::size_t i = 0; i < c.fracture_sets.size(); ++i) {
    const FractureSetConfig& s = c.fracture_sets[i];
    const std::string key = item_key("fracture_sets", i);
    for (std::size_t j = 0; j < i; ++j)
      if (c.fracture_sets[j].name == s.name)
        m.fail(key + ".name", "duplicate set name '" + s.name + "' (also fracture_sets[" + std::to_string(j) +
                                  "]); names must be distinct");
    const auto clash = [&](const std::string& list, std::size_t j) {
      m.fail(key + ".name", "'" + s.name + "' is also the name of " + item_key(list, j) +
                                "; a set's name must differ from those of fractures, fracture maps and "
                                "breakable patterns (it names its fractures)");
    };
    for (std::size_t j = 0; j < c.fractures.size(); ++j)
      if (c.fractures[j].name == s.name) clash("fractures", j);
    for (std::size_t j = 0; j < c.fracture_maps.size(); ++j)
      if (c.fracture_maps[j].name == s.name) clash("fracture_maps", j);
    for (std::size_t j = 0; j < c.breakable_patterns.size(); ++j)
      if (c.breakable_patterns[j].name == s.name) clash("breakable_patterns", j);
    const FractureLengthConfig& l = s.length;
    const bool lognormal = l.distribution == "lognormal";
    const std::optional<double> shortest = lognormal ? l.median_m : l.min_m;
    const std::string name = lognormal ? "median" : "min";
    if (shortest && *shortest > diagonal)
      m.fail(key + ".length." + name, "must be <= the diagonal of domain.outer, " + format_number(diagonal) +
                                          " m: no fracture could be that long (got " + format_number(*shortest) +
                                          ")");
  }
}

}  // namespace hfdda::io
