// The key tables of the case file: one table per section of CaseConfig, in the order
// docs/case_file.md lists them. Declarative: each row names a key, its unit, allowed
// range, seed source and description, and the field kind that reads it (case_fields.hpp).
// Checks on one complete list item sit next to the item's table; checks across
// sections are in case_checks.cpp.

#include "io/case_tables.hpp"

#include "io/breakable_patterns.hpp"
#include "io/fracture_maps.hpp"
#include "io/fracture_sets.hpp"
#include "io/case_fields.hpp"
#include "io/load_ramp_keys.hpp"
#include "io/sampled_fields.hpp"
#include "io/solver_control_tables.hpp"

namespace hfdda::io {

using namespace schema;

namespace {

/// fixed_points: a list of [x, y], replaced as a whole.
Field<CaseConfig> fixed_point_list(Doc d) {
  auto read = [](FileReader& r, const YAML::Node& n, const std::string& key, CaseConfig& out) {
    if (!n.IsSequence()) r.fail(n, key, "expected a list of points (got " + describe(n) + ")");
    check_item_count(r, n, key);
    r.forget(key + "[");
    std::vector<FixedPointConfig> points;
    for (std::size_t i = 0; i < n.size(); ++i) {
      r.set_null_line(r.line(n));
      r.record(item_key(key, i), n[i]);
      points.push_back(FixedPointConfig{read_point(r, n[i], item_key(key, i)), r.line(n[i])});
    }
    out.fixed_points = std::move(points);
  };
  return {key_doc(d, "list of [x, y]", "none", "at most 10000, each inside domain.outer"), read};
}

// --- Sections ---------------------------------------------------------------

const Table<DomainConfig>& domain_table() {
  static const Table<DomainConfig> table{
      "`domain`",
      "",
      {rect({"outer", "m", "§3.1: 100 m x 100 m",
             "outer boundary of the rock; far-field tractions act on its sides"},
            &DomainConfig::outer, "xmin < xmax, ymin < ymax"),
       optional_rect({"inner", "m", "§3.1: 36 m x 24 m; §3.4: 40 m x 40 m",
                      "finer, separately meshed inner domain; null removes an inherited one"},
                     &DomainConfig::inner, "strictly inside outer")}};
  return table;
}

const Table<MeshConfig>& mesh_table() {
  static const Table<MeshConfig> table{
      "`mesh`",
      "`cell_size`, `outer_growth` and `split` apply to structured meshes; `max_area_inner`, "
      "`max_area_outer`, `min_angle` and `snap_tolerance` to Delaunay meshes.",
      {choice({"type", "", "§3.1 grid; §3.3, §5.2 constrained Delaunay",
               "structured grid or constrained Delaunay triangulation"},
              &MeshConfig::kind,
              Choices<MeshKind>{{"structured", MeshKind::structured},
                                {"delaunay", MeshKind::delaunay}}),
       number({"cell_size", "m", "§3.1: joints 1 m apart; §3.2: 0.5 to 4 m",
               "side of the square cells inside the inner rectangle"},
              &MeshConfig::cell_size_m, greater_than(0), kWithinDomain),
       number({"outer_growth", "-", "§3.1: coarser outer domain",
               "ratio of successive cell sizes from the inner rectangle outwards"},
              &MeshConfig::outer_growth, interval(1, false, 10, false)),
       choice({"split", "", "§3.1: quadrilaterals vs triangles",
               "quadrilateral cells kept whole or split into 2 or 4 triangles"},
              &MeshConfig::split,
              Choices<mesh::CellSplit>{{"none", mesh::CellSplit::none},
                                       {"two", mesh::CellSplit::two},
                                       {"four", mesh::CellSplit::four}}),
       number({"max_area_inner", "m^2", "§3.3: 30 mm^2; §5.2: 2 cm^2",
               "largest triangle area inside the inner rectangle (everywhere without one)"},
              &MeshConfig::max_area_inner_m2, greater_than(0), kAreaWithinDomain),
       number({"max_area_outer", "m^2", "§5.5: 50 m^2",
               "largest triangle area outside the inner rectangle"},
              &MeshConfig::max_area_outer_m2, greater_than(0), kAreaWithinDomain),
       number({"min_angle", "deg", "", "minimum triangle angle of the Delaunay refinement"},
              &MeshConfig::min_angle_deg, interval(0, true, 30, false)),
       number({"snap_tolerance", "m", "",
               "fracture ends closer than this to another fracture or to a side of the domain are moved onto "
               "it (digitised near-misses made to meet; each move is reported in summary.json); 0: 5e-7 of "
               "the domain's diagonal"},
              &MeshConfig::snap_tolerance_m, at_least(0), kWithinDomain)}};
  return table;
}

/// Region 'box' is what a box is for, so each needs the other.
void check_material_item(const FileReader& r, const YAML::Node& item, const std::string& key,
                         const MaterialConfig& material, const std::set<std::string>& seen) {
  if (material.region == "box" && !seen.contains("box"))
    r.fail(item["region"], key + ".region", "region 'box' needs a 'box' rectangle");
  if (material.region != "box" && seen.contains("box"))
    r.fail(item["box"], key + ".box",
           "is only used with region 'box' (region is '" + material.region + "')");
}

const Table<MaterialConfig>& material_table() {
  static const Table<MaterialConfig> table{
      "`materials[]` items",
      "Zones are applied in order; a later zone overrides an earlier one (by block centroid). "
      "`box` is given exactly when `region` is `box`.",
      {text({"name", "", "", "label used in outputs"}, &MaterialConfig::name),
       choice({"region", "", "§3.3: softer outer blocks",
               "where it applies: everywhere, inside or outside domain.inner, or in box"},
              &MaterialConfig::region,
              Choices<std::string>{{"all", "all"}, {"inner", "inner"}, {"outer", "outer"},
                                   {"box", "box"}}),
       rect({"box", "m", "", "zone of region 'box'"}, &MaterialConfig::box,
            "overlaps domain.outer", "none"),
       sampled_number({"youngs_modulus", "Pa", "Table 3.1: E = 25 GPa; §5.5, Tables 5.5, 5.6: triangular",
                       "Young's modulus; the contact and fixed-point springs scale with the largest value it can "
                       "take"},
              &MaterialConfig::youngs_modulus_Pa, &MaterialConfig::youngs_modulus_law,
              interval(kMinYoungsModulus, false, kMaxModulus, false), SamplingScope::block,
              "from gelatin, the softest solid fractured in laboratory experiments (1e3 to 1e4 Pa), "
              "to above any solid (diamond: 1.2e12)"),
       sampled_number({"poissons_ratio", "-", "Table 3.1: nu = 0.25; §5.5, Tables 5.5, 5.6: triangular",
                       "Poisson's ratio (plane strain)"},
                      &MaterialConfig::poissons_ratio, &MaterialConfig::poissons_ratio_law,
                      interval(0, false, 0.5, true), SamplingScope::block),
       number({"density", "kg/m^3", "Table 3.1: rho_r = 2650 kg/m^3", "rock density"},
              &MaterialConfig::density_kg_m3, positive_up_to(kMaxDensity),
              "above any solid (osmium: 2.3e4)")}};
  return table;
}

/// joints.tensile_strength: written in a later file of the extends chain, it replaces an
/// inherited fracture_toughness (the later file's choice wins).
Field<JointConfig> joint_tensile_strength() {
  Field<JointConfig> field =
      sampled_number({"tensile_strength", "Pa",
                      "Table 3.1: T0 = 0; Table 5.1: T0 = 6 MPa; §5.5, Tables 5.5, 5.6: triangular on log10",
                      "tensile strength T0 of intact bonds (seed eq. 2.16)"},
                     &JointConfig::tensile_strength_Pa, &JointConfig::tensile_strength_law, zero_to(kMaxStrength),
                     SamplingScope::joint);
  field.read = [read = field.read](FileReader& r, const YAML::Node& n, const std::string& key, JointConfig& out) {
    read(r, n, key, out);
    out.fracture_toughness_Pa_sqrt_m.reset();
  };
  return field;
}

void check_joints(const FileReader& r, const YAML::Node& map, const std::string& key, const JointConfig&,
                  const std::set<std::string>& seen) {
  check_strength_choice(r, map, key, seen);
}

const Table<JointConfig>& joint_table() {
  static const Table<JointConfig> table{
      "`joints`",
      "Every joint (bond between two blocks) takes these values unless a fracture on it "
      "overrides them. Give `tensile_strength` or `fracture_toughness`, not both, in one map; "
      "a file that `extends` another replaces the inherited choice with its own.",
      {joint_tensile_strength(),
       fracture_toughness_key("T0 of intact bonds", &JointConfig::fracture_toughness_Pa_sqrt_m, "none"),
       number({"cohesion", "Pa", "Tables 5.1, 5.3: C0",
               "cohesion C0 of intact bonds (seed eq. 2.16)"},
              &JointConfig::cohesion_Pa, zero_to(kMaxStrength)),
       sampled_number({"friction_angle", "deg", "Table 3.1: phi = 30 deg; §5.5, Tables 5.5, 5.6: triangular",
                       "friction angle phi"},
                      &JointConfig::friction_angle_deg, &JointConfig::friction_angle_law,
                      interval(0, false, 90, true), SamplingScope::joint),
       sampled_number({"hydraulic_width", "m", "Table 5.1: natural fracture w0 = 1 um",
                       "w0: width through which fluid flows along a mechanically closed joint (the hydraulic width "
                       "is the opening plus w0); 0: fluid enters a joint only once it opens"},
                      &JointConfig::hydraulic_width_m, &JointConfig::hydraulic_width_law,
                      zero_to(kMaxHydraulicWidth), SamplingScope::joint),
       boolean({"breakable", "", "§2.3", "false: intact bonds never break"},
               &JointConfig::breakable),
       choice({"breakable_region", "", "§3.4: fracturing in the inner domain only",
               "all, or inner: only joints between two blocks whose centroids lie in domain.inner "
               "may break (a fracture's `breakable` still overrides)"},
              &JointConfig::breakable_region, Choices<std::string>{{"all", "all"}, {"inner", "inner"}})}};
  return table;
}

/// A fracture is a line: its ends must differ. Fluid can only fill joints that start
/// open, and the pressure of fluid-filled joints is solved for, not prescribed. Each
/// flagged value was written in this item (list items start from the defaults).
void check_fracture_item(const FileReader& r, const YAML::Node& item, const std::string& key,
                         const FractureConfig& fracture, const std::set<std::string>& seen) {
  check_strength_choice(r, item, key, seen);
  if (fracture.from == fracture.to)
    r.fail(item["to"], key + ".to",
           "must differ from 'from' (both are " + format_point(fracture.from) + ")");
  if (fracture.fluid_filled && !fracture.initially_open)
    r.fail(item["fluid_filled"], key + ".fluid_filled",
           "fluid_filled: true needs initially_open: true on the same fracture");
  if (fracture.fluid_filled && fracture.pressure_Pa)
    r.fail(item["pressure"], key + ".pressure",
           "cannot be prescribed on a fracture with fluid_filled: true (its pressure is "
           "solved for); give one or the other");
  if (fracture.initial_width_m > 0 && !fracture.fluid_filled)
    r.fail(item["initial_width"], key + ".initial_width",
           "is only used with fluid_filled: true (got " +
               format_number(fracture.initial_width_m) + ")");
  if (fracture.initial_pressure_Pa > 0 && !fracture.fluid_filled)
    r.fail(item["initial_pressure"], key + ".initial_pressure",
           "is only used with fluid_filled: true (got " +
               format_number(fracture.initial_pressure_Pa) + ")");
  if (fracture.initial_opening == InitialOpening::elastic) {
    if (!fracture.fluid_filled)
      r.fail(item["initial_opening"], key + ".initial_opening",
             "elastic is only used with fluid_filled: true (it sets the width of the fluid it starts with)");
    if (fracture.initial_width_m > 0)
      r.fail(item["initial_width"], key + ".initial_width",
             "cannot be given with initial_opening: elastic (the opening under initial_pressure is the width; "
             "got " + format_number(fracture.initial_width_m) + ")");
    if (!(fracture.initial_pressure_Pa > 0))
      r.fail(item["initial_opening"], key + ".initial_opening",
             "elastic needs initial_pressure > 0 on the same fracture (the pressure that opens it)");
  }
}

const Table<FractureConfig>& fracture_table() {
  static const Table<FractureConfig> table{
      "`fractures[]` items",
      "A straight line feature: initial fracture, natural fracture, prescribed path or "
      "interface. Joints lying on it take its values; unset values come from `joints`. "
      "Its own `tensile_strength` or `fracture_toughness` (not both) wins over the choice "
      "of `joints`. "
      "`from` and `to` differ. `fluid_filled: true` needs `initially_open: true` and "
      "excludes `pressure`; `initial_width` > 0 and `initial_pressure` > 0 need "
      "`fluid_filled: true`; `initial_opening: elastic` needs `fluid_filled: true` and `initial_pressure` > 0, "
      "and excludes `initial_width`. `pressure` and `segment_length` have further rules in the checks across keys.",
      {text({"name", "", "", "label used in outputs"}, &FractureConfig::name),
       required(point({"from", "m", "§3.1: 20 m fracture at the centre", "first end"},
                      &FractureConfig::from, "inside domain.outer")),
       required(point({"to", "m", "", "second end"}, &FractureConfig::to,
                      "inside domain.outer")),
       number({"segment_length", "m", "§3.1: joints 1 m apart",
               "Delaunay mesh: the fracture is a constraint split into equal pieces no longer than this, its "
               "joints (the refinement may split a piece further); 0: pieces of the mesh size. A structured mesh "
               "makes a fracture of its cell edges and takes no segment_length"},
              &FractureConfig::segment_length_m, at_least(0),
              std::string(kWithinDomain) + "; > 0 only with mesh.type: delaunay, then >= 0.01 of the mesh size it "
              "meets (checks across keys)"),
       boolean({"initially_open", "", "§3.2: joints at the injection point start open",
                "bonds on the line are broken at t = 0"},
               &FractureConfig::initially_open),
       boolean({"natural", "", "Tables 5.1, 5.3: natural fractures",
                "pre-existing natural fracture"},
               &FractureConfig::natural),
       optional_boolean({"breakable", "", "§4.5: fracturing confined to one line",
                         "whether its intact bonds may break"},
                        &FractureConfig::breakable, "joints.breakable"),
       optional_sampled_number({"tensile_strength", "Pa", "Table 5.1: natural fracture T0 = 0",
                                "tensile strength T0 of its bonds"},
                               &FractureConfig::tensile_strength_Pa, &FractureConfig::tensile_strength_law,
                               zero_to(kMaxStrength), "joints.tensile_strength", SamplingScope::joint),
       fracture_toughness_key("T0 of its bonds", &FractureConfig::fracture_toughness_Pa_sqrt_m,
                              "joints.fracture_toughness"),
       optional_number({"cohesion", "Pa", "Table 5.1: natural fracture C0 = 0",
                        "cohesion C0 of its bonds"},
                       &FractureConfig::cohesion_Pa, zero_to(kMaxStrength), "joints.cohesion"),
       optional_sampled_number({"friction_angle", "deg", "Table 5.1: natural fracture phi = 35 deg",
                                "friction angle of its joints"},
                               &FractureConfig::friction_angle_deg, &FractureConfig::friction_angle_law,
                               interval(0, false, 90, true), "joints.friction_angle", SamplingScope::joint),
       optional_sampled_number({"hydraulic_width", "m", "Table 5.1: natural fracture w0 = 1 um",
                                "w0 of its joints: fluid invades them through this width while they are closed"},
                               &FractureConfig::hydraulic_width_m, &FractureConfig::hydraulic_width_law,
                               zero_to(kMaxHydraulicWidth), "joints.hydraulic_width", SamplingScope::joint),
       optional_number({"pressure", "Pa", "§3.1: 9.81 MPa",
                        "fluid pressure prescribed on the faces of its open joints: from t = 0 with "
                        "initially_open: true; without it only on joints that break open during the run, so "
                        "they must be breakable and some fracture initially open"},
                       &FractureConfig::pressure_Pa, zero_to(kMaxStress), "none"),
       boolean({"fluid_filled", "",
                "§3.2: the two fractures on either side of the injection point were "
                "initially opened",
                "its open joints hold fluid (at `initial_pressure`) and belong to the flow "
                "network from t = 0; needs a `fluid` section. A network of hundreds of such joints "
                "at zero pressure may not get through its first flow solve: start it at a pressure "
                "with `initial_opening: elastic` (docs/when_a_run_stops.md)"},
               &FractureConfig::fluid_filled),
       number({"initial_width", "m", "",
               "initial aperture of its fluid-filled joints; 0: the minimum width "
               "(numerics.min_width_main)"},
              &FractureConfig::initial_width_m, at_least(0),
              std::string(kWithinDomain) + ", > 0 only with fluid_filled"),
       choice({"initial_opening", "", "none (HFDDA): the seed's fluid-filled starts are at zero pressure",
               "where the initial aperture of its fluid-filled joints comes from: width (initial_width, the "
               "rock not yet opened, so that in the first steps the fluid is squeezed out under the closing "
               "limit) or elastic (the opening of the rock under initial_pressure and the loads of the first "
               "step, from steps before it repeated until no joint end moves by more than 1 % of its "
               "aperture, at most 10: the fluid starts in equilibrium; summary.json initial_opening says how "
               "it settled; docs/design_notes.md section 31)"},
              &FractureConfig::initial_opening,
              Choices<InitialOpening>{{"width", InitialOpening::width}, {"elastic", InitialOpening::elastic}}),
       number({"initial_pressure", "Pa",
               "§3.3: notch fluid at 0.08 % compression by mass, i.e. 0.0008 K_f",
               "initial fluid pressure of its fluid-filled joints: they hold rho(p) times "
               "their volume (fluid.bulk_modulus, eq. 2.6)"},
              &FractureConfig::initial_pressure_Pa, zero_to(kMaxStress), "> 0 only with fluid_filled")}};
  return table;
}

const Table<FluidConfig>& fluid_table() {
  static const Table<FluidConfig> table{
      "`fluid`",
      "Present, the flow network of the fracture joints is solved, coupled with the "
      "blocks; missing keys take the defaults below. Compressible fluid, rho = rho0 (1 + "
      "(p - p0) / K_f) (seed eq. 2.6); cubic law with viscosity mu (eq. 2.2).",
      {number({"density", "kg/m^3", "Table 3.1: rho_f = 1000 kg/m^3",
               "reference density rho0, at the reference pressure"},
              &FluidConfig::density_kg_m3, interval(kMinFluidDensity, false, kMaxDensity, false),
              "from below any gas at atmospheric pressure (hydrogen: 0.09)"),
       number({"bulk_modulus", "Pa", "Table 3.1: K_f = 2.2 GPa",
               "bulk modulus K_f; compressibility c_f = 1 / K_f"},
              &FluidConfig::bulk_modulus_Pa, interval(kMinFluidBulkModulus, false, kMaxModulus, false),
              "from a gas at atmospheric pressure (isothermal K = p = 1e5 Pa; liquids: 1e9 to 1e10), "
              "below which fluid storage swamps the mass balance"),
       sampled_number({"viscosity", "Pa s", "Table 3.1: mu = 1 mPa s; Table 5.3: 20 mPa s; §5.5, §5.6: triangular",
                       "dynamic viscosity mu"},
                      &FluidConfig::viscosity_Pa_s, &FluidConfig::viscosity_law,
                      interval(kMinViscosity, false, 1e6, false), SamplingScope::realisation,
              "from below any gas (hydrogen: 9e-6 Pa s); the cubic-law conductance grows as 1 / mu"),
       number({"reference_pressure", "Pa", "eq. 2.6: p0",
               "pressure p0 at which the density is rho0"},
              &FluidConfig::reference_pressure_Pa, magnitude_up_to(kMaxStress)),
       number({"leak_off_coefficient", "m/s^0.5", "§3.4: C_L = 0.02 mm/s^0.5 = 2e-5",
               "Carter coefficient C_L of one fracture wall; 0: no leak-off. Both walls "
               "leak: a wetted joint of length L loses 2 C_L L / sqrt(t - t0) per metre of "
               "depth, t0 the time fluid reached it (the seed's eq. 2.3 counts one wall; "
               "erratum 4 in docs/seed_errata.md); a partly filled node leaks through its "
               "wetted fraction only, so no node loses more than it holds"},
              &FluidConfig::leak_off_coefficient_m_sqrt_s, zero_to(1)),
       choice({"edge", "", "§5.2: a laboratory block, whose fluid escapes at its edge",
               "sealed: no fluid leaves through the boundary of domain.inner; vented: a point of that "
               "boundary reached by fluid is held at zero pressure, fills, and passes on what it cannot "
               "hold (counted as mass_vented_kg); needs domain.inner"},
              &FluidConfig::edge, Choices<std::string>{{"sealed", "sealed"}, {"vented", "vented"}})}};
  return table;
}

const Table<InjectionConfig>& injection_table() {
  static const Table<InjectionConfig> table{
      "`injections[]` items",
      "A fluid source at the mesh vertex nearest `at`; needs a `fluid` section.",
      {text({"name", "", "", "label used in outputs"}, &InjectionConfig::name),
       required(point({"at", "m", "§3.2: injection at the origin",
                       "injection point: a mesh point (within 1e-6 of the domain size) on a joint of a `fluid_filled` fracture"},
                      &InjectionConfig::at, "inside domain.outer")),
       required(sampled_number({"mass_rate", "kg/s", "§3.2: Q0 = 4 kg/s; §3.4: 1 kg/s; §5.5, §5.6: triangular",
                                "injected mass per second and per metre of out-of-plane thickness"},
                               &InjectionConfig::mass_rate_kg_s, &InjectionConfig::mass_rate_law,
                               positive_up_to(1e6), SamplingScope::realisation)),
       number({"start_time", "s", "", "time at which injection starts (then continues)"},
              &InjectionConfig::start_time_s, zero_to(kMaxTime)),
       optional_number({"mass_limit", "kg", "§5.5: injection stopped after 60 kg",
                        "injection stops once this mass per metre of out-of-plane thickness has gone in; "
                        "the run goes on shut in to time.end_time"},
                       &InjectionConfig::mass_limit_kg, positive_up_to(1e12), "no limit"),
       number({"system_compliance", "m^2/Pa", "none (HFDDA); §3.3 models the pump's delay by a late start",
               "compliance of the injection system (pump, lines, borehole) per metre of out-of-plane thickness: "
               "at injection pressure p it holds rho(0) C p more fluid than at zero pressure, taken from the "
               "pump's flow as the pressure rises and given back as it falls; 0: all of the flow enters the "
               "fracture. Needs the fluid at its point to start at zero pressure"},
              &InjectionConfig::system_compliance_m2_Pa, zero_to(1e-3))}};
  return table;
}

const Table<ProbeConfig>& probe_table() {
  static const Table<ProbeConfig> table{
      "`probes[]` items",
      "A gauge read at the mesh vertex nearest `at` every step; its pressure and its "
      "hydraulic aperture (mean aperture of the fluid-filled joints meeting at the "
      "vertex, 0 where none does) are the history.csv columns "
      "`probe_<name>_pressure_Pa` and `probe_<name>_aperture_m`, so names are distinct "
      "and use letters, digits and `_` only. Needs a `fluid` section.",
      {required(identifier({"name", "", "", "gauge name, part of the output column names"},
                           &ProbeConfig::name)),
       required(point({"at", "m", "", "gauge location (the nearest mesh vertex is used)"},
                      &ProbeConfig::at, "inside domain.outer"))}};
  return table;
}

const Table<FarFieldConfig>& far_field_table() {
  static const Table<FarFieldConfig> table{
      "`far_field`",
      "Far-field stress, tension positive, applied as tractions t = sigma . n on the listed "
      "sides of `domain.outer` (a 5 MPa compression is `syy: -5e6`).",
      {sampled_number({"sxx", "Pa", "Table 5.4: sigma_1, sigma_3; §5.6, Table 5.6: triangular",
                       "normal stress along x"},
                      &FarFieldConfig::sxx_Pa, &FarFieldConfig::sxx_law, magnitude_up_to(kMaxStress),
                      SamplingScope::realisation, "10 x the strength of the strongest rock"),
       sampled_number({"syy", "Pa", "§3.1: 5 MPa background stress; §5.6, Table 5.6: triangular",
                       "normal stress along y"},
                      &FarFieldConfig::syy_Pa, &FarFieldConfig::syy_law, magnitude_up_to(kMaxStress),
                      SamplingScope::realisation, "10 x the strength of the strongest rock"),
       sampled_number({"sxy", "Pa", "", "shear stress"}, &FarFieldConfig::sxy_Pa, &FarFieldConfig::sxy_law,
                      magnitude_up_to(kMaxStress), SamplingScope::realisation,
                      "10 x the strength of the strongest rock"),
       choice_list({"sides", "", "§3.1: upper and lower boundaries",
                    "sides of domain.outer loaded by the far-field stress; the traction sigma . n puts sxx on "
                    "left and right, syy on bottom and top, so a non-zero sxx needs left or right, a non-zero "
                    "syy bottom or top, and a non-zero stress some side"},
                   &FarFieldConfig::sides, {"left", "right", "bottom", "top"}),
       boolean({"in_situ", "", "",
                "the rock starts stressed and in equilibrium (block stresses, joint contact "
                "forces, tractions on all four sides; `sides` is then ignored); false: loaded "
                "by the boundary tractions from rest, as the seed does"},
               &FarFieldConfig::in_situ)}};
  return table;
}

const Table<PointLoadConfig>& point_load_table() {
  static const Table<PointLoadConfig> table{
      "`point_loads[]` items",
      "",
      {point({"at", "m", "", "point of application"}, &PointLoadConfig::at,
             "inside domain.outer"),
       point({"force", "N/m", "", "force per metre of out-of-plane thickness"},
             &PointLoadConfig::force_N_per_m, "each component", magnitude_up_to(kMaxPointForce))}};
  return table;
}

const Table<EnsembleConfig>& ensemble_table() {
  static const Table<EnsembleConfig> table{
      "`ensemble`",
      "A Monte Carlo ensemble of the case, run by `hfdda ensemble` (docs/ensembles.md); "
      "`hfdda run` ignores it.",
      {integer({"realisations", "", "§5.5, §5.6: 50 realisations", "number of realisations"},
               &EnsembleConfig::realisations, interval(1, false, 1000000, false)),
       integer({"master_seed", "", "§5.5: \"all distributions were sampled using pre-defined seeds\"",
                "seed of every random stream of the ensemble: realisation i draws from streams that "
                "depend only on master_seed and i"},
               &EnsembleConfig::master_seed, interval(0, false, 2147483647, false)),
       choice_list({"resample", "", "§5.5: reservoir held constant, fluid varied",
                    "groups drawn anew for every realisation; the others are drawn once and held: "
                    "network (the fracture_sets network), rock (materials, joints, far_field), "
                    "natural_fractures (properties of fractures and fracture_sets), fluid (fluid, injections)"},
                   &EnsembleConfig::resample, {"network", "rock", "natural_fractures", "fluid"}),
       number({"map_every", "s", "§5.5: maps every 15 min", "likelihood maps at every multiple of this time"},
              &EnsembleConfig::map_every_s, positive_up_to(kMaxTime), "<= time.end_time"),
       number({"grid_cell", "m", "Figures 5.24-5.44", "side of the square cells of the grid maps"},
              &EnsembleConfig::grid_cell_m, positive_up_to(kMaxCoordinate), kWithinDomain)}};
  return table;
}

const Table<OutputConfig>& output_table() {
  static const Table<OutputConfig> table{
      "`output`",
      "",
      {integer({"every_steps", "", "",
                "joint CSV and VTU every n steps and always at the end; 0: end only"},
               &OutputConfig::every_steps, interval(0, false, kMaxSteps, false),
               "the most steps a run may have"),
       boolean({"vtu", "", "", "write VTU files"}, &OutputConfig::vtu)}};
  return table;
}

/// `extends` is resolved by the loader before the other keys; here it is only declared.
Field<CaseConfig> extends_key() {
  auto read = [](FileReader&, const YAML::Node&, const std::string&, CaseConfig&) {};
  return {key_doc({"extends", "", "",
                   "base case file, read first; path relative to this file"},
                  "string", "none", "a readable case file, no cycle"),
          read};
}

}  // namespace

const Table<CaseConfig>& case_table() {
  static const Table<CaseConfig> table{
      "Top level",
      "",
      {text({"title", "", "", "case title"}, &CaseConfig::title),
       extends_key(),
       section({"domain", "", "", "outer and inner rectangles"}, &CaseConfig::domain,
               &domain_table),
       section({"mesh", "", "", "block mesh"}, &CaseConfig::mesh, &mesh_table),
       map_list({"materials", "", "Tables 3.1, 3.2, 5.1, 5.4: rock parameters",
                 "elastic material zones"},
                &CaseConfig::materials, &material_table, 1,
                "one material with the item defaults", check_material_item),
       section({"joints", "", "Table 3.1: fracture parameters", "default joint strength"},
               &CaseConfig::joints, &joint_table, check_joints),
       map_list({"fractures", "", "§3.1-3.5, §5.2-5.4", "line features"},
                &CaseConfig::fractures, &fracture_table, 0, "none", check_fracture_item),
       breakable_patterns_key(),
       fracture_maps_key(),
       fracture_sets_key(),
       network_seed_key(),
       integer({"random_seed", "", "§5.5: \"all distributions were sampled using pre-defined seeds\"",
                "seed of the draws of the keys given as distributions: the same seed gives the same values on "
                "every machine; it leaves the network of fracture_sets alone (network_seed sets that)"},
               &CaseConfig::random_seed, interval(0, false, 2147483647, false),
               "only with a key given as a distribution"),
       section({"far_field", "", "§3.1: background stress", "far-field stress"},
               &CaseConfig::far_field, &far_field_table),
       load_ramp_key(),
       map_list({"point_loads", "", "", "concentrated forces"}, &CaseConfig::point_loads,
                &point_load_table, 0, "none"),
       point({"body_force", "N/m^3", "", "body force per unit volume, e.g. [0, -rho g]"},
             &CaseConfig::body_force_N_m3, "1000 g in rock; each component", magnitude_up_to(kMaxBodyForce)),
       fixed_point_list({"fixed_points", "m", "§3.3, §5.2: outer boundary fixed at corners",
                         "points held fixed (stiff springs)"}),
       optional_section({"fluid", "", "Table 3.1: fluid parameters",
                         "fracturing fluid; present: the coupled flow network is solved"},
                        &CaseConfig::fluid, &fluid_table),
       map_list({"injections", "", "§3.2: Q0 at the origin", "fluid sources"},
                &CaseConfig::injections, &injection_table, 0, "none"),
       map_list({"probes", "", "", "pressure and aperture gauges"}, &CaseConfig::probes,
                &probe_table, 0, "none"),
       section({"contact", "", "Table 3.1: numerical parameters", "contact model"},
               &CaseConfig::contact, &contact_table),
       section({"numerics", "", "§2.1, §2.3, §2.4", "iterations and tolerances"},
               &CaseConfig::numerics, &numerics_table),
       section({"fracture", "", "§2.3", "failure criterion of intact joints"}, &CaseConfig::fracture,
               &fracture_criterion_table),
       section({"time", "", "Table 3.1: time step", "time stepping"}, &CaseConfig::time,
               &time_table),
       section({"output", "", "", "what is written"}, &CaseConfig::output, &output_table),
       optional_section({"ensemble", "", "§5.5, §5.6: Monte Carlo realisations",
                         "likelihood maps over realisations (`hfdda ensemble`)"},
                        &CaseConfig::ensemble, &ensemble_table)}};
  return table;
}

}  // namespace hfdda::io
