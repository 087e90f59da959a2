// Checks across keys of the merged case (case_checks.hpp). The rule text of each check
// is also its line in docs/case_file.md.

#include "io/case_checks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "io/breakable_patterns.hpp"
#include "io/fracture_sets.hpp"
#include "io/load_ramp_keys.hpp"

namespace hfdda::io {

using namespace schema;

bool has_distributions(const CaseConfig& c) {
  bool any = c.joints.tensile_strength_law || c.joints.friction_angle_law || c.joints.hydraulic_width_law ||
             c.far_field.sxx_law || c.far_field.syy_law || c.far_field.sxy_law ||
             (c.fluid && c.fluid->viscosity_law);
  for (const MaterialConfig& z : c.materials) any = any || z.youngs_modulus_law || z.poissons_ratio_law;
  for (const FractureConfig& f : c.fractures)
    any = any || f.tensile_strength_law || f.friction_angle_law || f.hydraulic_width_law;
  for (const FractureSetConfig& s : c.fracture_sets)
    any = any || s.tensile_strength_law || s.friction_angle_law || s.hydraulic_width_law;
  for (const InjectionConfig& i : c.injections) any = any || i.mass_rate_law;
  return any;
}

std::string domain_text(const Rect& r) {
  std::string text = "[";  // appended: `"[" + std::string` trips a false -Wrestrict in GCC 12
  text += format_number(r.xmin) + ", " + format_number(r.xmax) + "] x [" +
          format_number(r.ymin) + ", " + format_number(r.ymax) + "]";
  return text;
}

namespace {

std::string parent_key(const std::string& key) {
  const auto cut = key.find_last_of(".[");
  return cut == std::string::npos ? std::string() : key.substr(0, cut);
}

}  // namespace

void MergedChecker::fail(const std::string& key, const std::string& rule) const {
  std::string k = key;
  while (!k.empty() && !present(k)) k = parent_key(k);
  const Location loc = k.empty() ? Location{top_file_, 0} : where_->at(k);
  throw InputError(loc.file, loc.line, key, rule);
}

namespace {

void check_point_in_domain(const CaseConfig& c, const MergedChecker& m, const Vec2& p,
                           const std::string& key) {
  if (!c.domain.outer.contains(p))
    m.fail(key, "lies outside the domain " + domain_text(c.domain.outer) + " (got " +
                    format_point(p) + ")");
}

void check_inner_inside_outer(const CaseConfig& c, const MergedChecker& m) {
  if (!c.domain.inner) return;
  const Rect& in = *c.domain.inner;
  const Rect& out = c.domain.outer;
  if (!(in.xmin > out.xmin && in.xmax < out.xmax && in.ymin > out.ymin && in.ymax < out.ymax))
    m.fail("domain.inner", "must lie strictly inside domain.outer " + domain_text(out) +
                               " (got " + domain_text(in) + ")");
}

void check_end_time(const CaseConfig& c, const MergedChecker& m) {
  if (c.time.end_time_s >= c.time.dt_s) return;
  const std::string values = "end_time " + format_number(c.time.end_time_s) + ", dt " +
                             format_number(c.time.dt_s);
  if (m.present("time.end_time") || !m.present("time.dt"))
    m.fail("time.end_time", "must be >= time.dt (got " + values + ")");
  m.fail("time.dt", "must be <= time.end_time (got " + values + "; end_time was not set and "
                    "defaults to " + format_number(TimeConfig{}.end_time_s) + ")");
}

/// At most kMaxSteps steps, and a whole number of them: the run ends at end_time.
/// A step count for a message: exact when it can be, else to 3 digits (1e-300 s steps
/// of 10 s are "about 1e+301", not 9.999999999999999e300).
std::string step_count_text(double steps) {
  if (steps < 1e15 && steps == std::round(steps)) return format_number(steps);
  char text[32];
  std::snprintf(text, sizeof text, "about %.3g", steps);
  return text;
}

void check_step_count(const CaseConfig& c, const MergedChecker& m) {
  if (c.load_ramp) return;  // levels, not end_time, set the steps (checked with load_ramp)
  const double steps = c.time.end_time_s / c.time.dt_s;
  const std::string key = m.present("time.end_time") || !m.present("time.dt") ? "time.end_time" : "time.dt";
  const std::string values =
      "end_time " + format_number(c.time.end_time_s) + " s, dt " + format_number(c.time.dt_s) + " s";
  if (steps > kMaxSteps)
    m.fail(key, "gives " + step_count_text(steps) + " time steps (" + values + "); at most " +
                    format_number(kMaxSteps) + " are allowed: raise dt or lower end_time");
  const double whole = std::round(steps);
  if (std::abs(steps - whole) > 1e-9 * std::max(1.0, steps)) {
    const double below = std::floor(steps) * c.time.dt_s, above = std::ceil(steps) * c.time.dt_s;
    m.fail(key, "is not a whole number of time steps (" + values + ": " + format_number(steps) +
                    " steps); the run would end at another time: make end_time a multiple of dt, e.g. " +
                    format_number(below) + " or " + format_number(above) + " s");
  }
}

/// Lengths no larger than the domain, and a mesh of at most kMaxCells cells.
void check_lengths(const CaseConfig& c, const MergedChecker& m) {
  const Rect& d = c.domain.outer;
  const double size = std::max(d.xmax - d.xmin, d.ymax - d.ymin);
  const double area = (d.xmax - d.xmin) * (d.ymax - d.ymin);
  const std::string side = "the larger side of domain.outer, " + format_number(size) + " m";
  auto length = [&](const std::string& key, double value) {
    if (value > size) m.fail(key, "must be <= " + side + " (got " + format_number(value) + ")");
  };
  auto area_at_most = [&](const std::string& key, double value) {
    if (value > area)
      m.fail(key, "must be <= the area of domain.outer, " + format_number(area) + " m^2 (got " +
                      format_number(value) + ")");
  };
  if (c.mesh.kind == MeshKind::structured) {
    length("mesh.cell_size", c.mesh.cell_size_m);
  } else {
    area_at_most("mesh.max_area_inner", c.mesh.max_area_inner_m2);
    if (c.domain.inner) area_at_most("mesh.max_area_outer", c.mesh.max_area_outer_m2);
    length("mesh.snap_tolerance", c.mesh.snap_tolerance_m);
  }
  length("contact.vertex_vertex_activation", c.contact.vertex_vertex_activation_m);
  for (std::size_t i = 0; i < c.fractures.size(); ++i) {
    length(item_key("fractures", i) + ".segment_length", c.fractures[i].segment_length_m);
    length(item_key("fractures", i) + ".initial_width", c.fractures[i].initial_width_m);
  }
  for (std::size_t i = 0; i < c.breakable_patterns.size(); ++i)
    length(item_key("breakable_patterns", i) + ".cell_size", c.breakable_patterns[i].cell_size_m);
  const Rect fine = c.domain.inner.value_or(d);
  const double fine_area = (fine.xmax - fine.xmin) * (fine.ymax - fine.ymin);
  double cells = 0;
  std::string key;
  if (c.mesh.kind == MeshKind::structured) {
    cells = fine_area / (c.mesh.cell_size_m * c.mesh.cell_size_m);
    key = "mesh.cell_size";
  } else {
    cells = fine_area / c.mesh.max_area_inner_m2 +
            (c.domain.inner ? (area - fine_area) / c.mesh.max_area_outer_m2 : 0.0);
    key = cells > 0 && fine_area / c.mesh.max_area_inner_m2 >= cells / 2 ? "mesh.max_area_inner"
                                                                        : "mesh.max_area_outer";
  }
  // A Delaunay mesh has at least a triangle on each side of every constraint piece.
  double piece_cells = 0, most_pieces = 0;
  for (std::size_t i = 0; c.mesh.kind == MeshKind::delaunay && i < c.fractures.size(); ++i) {
    const FractureConfig& f = c.fractures[i];
    if (f.segment_length_m <= 0) continue;
    const double pieces = std::ceil((f.to - f.from).norm() / f.segment_length_m);
    piece_cells += 2 * pieces;
    if (pieces > most_pieces) {
      most_pieces = pieces;
      if (2 * pieces > cells) key = item_key("fractures", i) + ".segment_length";
    }
  }
  if (cells + piece_cells > kMaxCells)
    m.fail(key, "would make about " + format_number(std::round(cells + piece_cells)) + " cells" +
                    (piece_cells > 0 ? " (" + format_number(std::round(piece_cells)) +
                                           " of them along the fracture pieces of segment_length)"
                                     : std::string()) +
                    "; at most " + format_number(kMaxCells) + " are allowed");
}

/// What segment_length is for: the length of the constraint pieces a Delaunay mesh
/// splits a fracture into. The refinement grades the triangles from the pieces to the
/// area bound, and stops checking angles of triangles with an edge below 1e-3 of the
/// mesh size (mesh/delaunay_mesh.cpp): around pieces that short it gives up or runs out
/// of memory, so pieces must be at least 10 times longer.
void check_segment_lengths(const CaseConfig& c, const MergedChecker& m) {
  for (std::size_t i = 0; i < c.fractures.size(); ++i) {
    const FractureConfig& f = c.fractures[i];
    const std::string key = item_key("fractures", i) + ".segment_length";
    if (f.segment_length_m <= 0) continue;
    if (c.mesh.kind == MeshKind::structured)
      m.fail(key, "is only used by a Delaunay mesh (mesh.type: delaunay); a structured mesh makes a fracture of "
                  "its cell edges, of mesh.cell_size (got " + format_number(f.segment_length_m) +
                      "); remove it or set mesh.type: delaunay");
    const bool inner_only = !c.domain.inner || (c.domain.inner->contains(f.from) && c.domain.inner->contains(f.to));
    const bool outer_larger = !inner_only && c.mesh.max_area_outer_m2 > c.mesh.max_area_inner_m2;
    const double area = outer_larger ? c.mesh.max_area_outer_m2 : c.mesh.max_area_inner_m2;
    const double size = std::sqrt(area);
    if (f.segment_length_m < kMinSegmentFraction * size)
      m.fail(key, "must be at least " + format_number(kMinSegmentFraction) + " of the mesh size it meets, sqrt(mesh." +
                      (outer_larger ? "max_area_outer" : "max_area_inner") + ") = " + format_number(size) +
                      " m, i.e. >= " + format_number(kMinSegmentFraction * size) + " m (got " +
                      format_number(f.segment_length_m) +
                      "): the Delaunay refinement cannot grade its triangles down to pieces that short; "
                      "0 gives pieces of the mesh size");
  }
}

}  // namespace

/// The traction of a stress on a side is sigma . n: sxx loads only the left and right
/// sides, syy only the bottom and top, sxy every side. A component that no listed side
/// carries would be dropped without a word.
void check_stress_sides(const MergedChecker& m, const std::string& section, double sxx, double syy, double sxy,
                        const std::vector<std::string>& sides, const std::string& what) {
  if (sxx == 0 && syy == 0 && sxy == 0) return;
  const auto has = [&](const char* side) { return std::find(sides.begin(), sides.end(), side) != sides.end(); };
  const std::string listed =
      section + ".sides is [" + join(sides, ", ") + "]" + (m.present(section + ".sides") ? "" : " (the default)");
  if (sides.empty())
    m.fail(section + ".sides", "is empty, so " + what + " (sxx " + format_number(sxx) + ", syy " + format_number(syy) +
                                   ", sxy " + format_number(sxy) + ") would act on no side and load nothing; list "
                                   "the sides it acts on");
  if (sxx != 0 && !has("left") && !has("right"))
    m.fail(section + ".sxx", "acts only on the left and right sides (the traction is sigma . n), but " + listed +
                                 ", with neither, so it would load nothing; add left and right to sides");
  if (syy != 0 && !has("bottom") && !has("top"))
    m.fail(section + ".syy", "acts only on the bottom and top sides (the traction is sigma . n), but " + listed +
                                 ", with neither, so it would load nothing; add bottom and top to sides");
}

namespace {

/// A stress component as the side checks see it: given as a distribution, its value of
/// largest magnitude (non-zero if the law can give anything but zero).
double largest_stress(double value, const ParameterLaw& law) {
  if (!law) return value;
  return std::abs(law->lowest()) > std::abs(law->highest()) ? law->lowest() : law->highest();
}

void check_far_field_sides(const CaseConfig& c, const MergedChecker& m) {
  if (c.far_field.in_situ) return;  // the in-situ stress acts on all four sides
  const FarFieldConfig& f = c.far_field;
  check_stress_sides(m, "far_field", largest_stress(f.sxx_Pa, f.sxx_law), largest_stress(f.syy_Pa, f.syy_law),
                     largest_stress(f.sxy_Pa, f.sxy_law), f.sides, "the far-field stress");
}

void check_random_seed(const CaseConfig& c, const MergedChecker& m) {
  if (m.present("random_seed") && !has_distributions(c))
    m.fail("random_seed", "is only used by keys given as distributions (there is none)");
}

/// A prescribed pressure loads the faces of open joints; on a bonded joint the bond
/// carries it and nothing happens. A fracture that is not initially open opens only
/// where its joints break, and a joint breaks only next to an open one (seed 2.3).
void check_pressure_applies(const CaseConfig& c, const MergedChecker& m) {
  bool any_open = false;
  for (const auto& f : c.fractures) any_open = any_open || f.initially_open;
  for (std::size_t i = 0; i < c.fractures.size(); ++i) {
    const FractureConfig& f = c.fractures[i];
    if (!f.pressure_Pa || f.initially_open) continue;
    const std::string key = item_key("fractures", i) + ".pressure";
    const std::string rule = "acts only on open joints: on a fracture without initially_open: true, only on joints "
                             "that break open during the run; ";
    if (!f.breakable.value_or(c.joints.breakable))
      m.fail(key, rule + "the joints of this one are not breakable (" +
                      (f.breakable ? "breakable: false" : "joints.breakable: false") +
                      "), so they stay bonded and the pressure would do nothing; give initially_open: true");
    if (!any_open)
      m.fail(key, rule + "a joint breaks only next to an open one, and no fracture is initially open, so the "
                         "pressure would do nothing; give initially_open: true");
  }
}

void check_material_regions(const CaseConfig& c, const MergedChecker& m) {
  for (std::size_t i = 0; i < c.materials.size(); ++i) {
    const MaterialConfig& mat = c.materials[i];
    const std::string key = item_key("materials", i);
    if ((mat.region == "inner" || mat.region == "outer") && !c.domain.inner)
      m.fail(key + ".region", "region '" + mat.region + "' needs domain.inner");
    const Rect& b = mat.box;
    const Rect& d = c.domain.outer;
    const bool overlaps = b.xmin < d.xmax && b.xmax > d.xmin && b.ymin < d.ymax && b.ymax > d.ymin;
    if (mat.region == "box" && !overlaps)
      m.fail(key + ".box", "must overlap the domain " + domain_text(d) + " (got " +
                               domain_text(b) + ")");
  }
}

void check_breakable_region(const CaseConfig& c, const MergedChecker& m) {
  if (c.joints.breakable_region == "inner" && !c.domain.inner)
    m.fail("joints.breakable_region", "region 'inner' needs domain.inner");
}

void check_vented_edge(const CaseConfig& c, const MergedChecker& m) {
  if (c.fluid && c.fluid->edge == "vented" && !c.domain.inner)
    m.fail("fluid.edge", "vented needs domain.inner (its boundary is the edge that vents)");
}

void check_stop_condition(const CaseConfig& c, const MergedChecker& m) {
  if (c.time.stop_when != "fluid_at_edge") return;
  if (!c.domain.inner) m.fail("time.stop_when", "fluid_at_edge needs domain.inner (its boundary is the edge)");
  if (!c.fluid) m.fail("time.stop_when", "fluid_at_edge needs a `fluid` section");
  if (c.load_ramp)
    m.fail("time.stop_when", "fluid_at_edge is a stop of time stepping; a load ramp has load_ramp.stop_when");
}

void check_fracture_criterion(const CaseConfig& c, const MergedChecker& m) {
  const bool energy = c.fracture.criterion == FailureCriterionKind::energy_release_rate;
  if (energy && !c.fracture.fracture_toughness_Pa_sqrt_m)
    m.fail("fracture.fracture_toughness", "is required with criterion: energy_release_rate (K_IC at crack tips)");
  for (const char* key : {"fracture_toughness", "mode2_toughness", "crack_closure"})
    if (!energy && m.present(std::string("fracture.") + key))
      m.fail(std::string("fracture.") + key, "is only used with criterion: energy_release_rate");
}

void check_intact_stiffness(const CaseConfig& c, const MergedChecker& m) {
  const double ratio = c.contact.intact_stiffness_ratio;
  if (!c.contact.two_tier || ratio == 1.0) return;
  const double factor = std::max(c.contact.normal_stiffness_factor, c.contact.shear_stiffness_factor);
  if (factor * ratio > kMaxStiffnessFactor)
    m.fail("contact.intact_stiffness_ratio",
           "times the larger of normal_stiffness and shear_stiffness is at most 1e6, beyond which the stiffness "
           "matrix loses all digits (got " + format_number(ratio) + " x " + format_number(factor) + ")");
}

void check_aperture_response(const CaseConfig& c, const MergedChecker& m) {
  if (c.numerics.aperture_response != ApertureResponse::converged_contacts) return;
  if (c.contact.method != ContactMethod::augmented_lagrangian)
    m.fail("numerics.aperture_response",
           "converged_contacts needs contact.method: alm (with penalty springs the response at fixed "
           "multipliers is the converged one)");
  if (c.numerics.flow_jacobian == FlowJacobianKind::krylov || c.numerics.flow_jacobian == FlowJacobianKind::augmented)
    m.fail("numerics.aperture_response",
           "converged_contacts is implemented for the dense flow Jacobian only (flow_jacobian: dense, or auto, "
           "which then stays dense)");
  const double factor = std::max(c.contact.normal_stiffness_factor, c.contact.shear_stiffness_factor) *
                        (c.contact.two_tier ? c.contact.intact_stiffness_ratio : 1.0);
  if (factor * kConvergedResponseStiffening > kMaxStiffnessFactor)
    m.fail("numerics.aperture_response",
           "converged_contacts stiffens the iterated springs 100 times; their stiffness factor (" +
               format_number(factor) + ") times 100 must stay at most 1e6, beyond which K loses all digits");
}

void check_fractures_in_domain(const CaseConfig& c, const MergedChecker& m) {
  for (std::size_t i = 0; i < c.fractures.size(); ++i) {
    check_point_in_domain(c, m, c.fractures[i].from, item_key("fractures", i) + ".from");
    check_point_in_domain(c, m, c.fractures[i].to, item_key("fractures", i) + ".to");
  }
}

void check_points_in_domain(const CaseConfig& c, const MergedChecker& m) {
  for (std::size_t i = 0; i < c.point_loads.size(); ++i)
    check_point_in_domain(c, m, c.point_loads[i].at, item_key("point_loads", i) + ".at");
  for (std::size_t i = 0; i < c.fixed_points.size(); ++i)
    check_point_in_domain(c, m, c.fixed_points[i].at, item_key("fixed_points", i));
  for (std::size_t i = 0; i < c.injections.size(); ++i)
    check_point_in_domain(c, m, c.injections[i].at, item_key("injections", i) + ".at");
  for (std::size_t i = 0; i < c.probes.size(); ++i)
    check_point_in_domain(c, m, c.probes[i].at, item_key("probes", i) + ".at");
}

/// Injections, probes and fluid-filled fractures are parts of the flow network.
void check_fluid_needed(const CaseConfig& c, const MergedChecker& m) {
  if (c.fluid) return;
  const std::string rule = "needs a 'fluid' section (none is given";
  const std::string removed = m.present("fluid") ? "; 'fluid: null' removed it)" : ")";
  if (!c.injections.empty()) m.fail("injections", "a fluid injection " + rule + removed);
  if (!c.probes.empty()) m.fail("probes", "a pressure probe " + rule + removed);
  for (std::size_t i = 0; i < c.fractures.size(); ++i)
    if (c.fractures[i].fluid_filled)
      m.fail(item_key("fractures", i) + ".fluid_filled", "fluid_filled: true " + rule + removed);
}

/// A flow network with no fluid in it and no source would stay empty.
void check_fluid_used(const CaseConfig& c, const MergedChecker& m) {
  if (!c.fluid || !c.injections.empty()) return;
  for (const auto& fracture : c.fractures)
    if (fracture.fluid_filled) return;
  m.fail("fluid", "needs at least one item in 'injections' or one fracture with "
                  "fluid_filled: true (there is neither)");
}

void check_probe_names(const CaseConfig& c, const MergedChecker& m) {
  for (std::size_t i = 0; i < c.probes.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (c.probes[i].name == c.probes[j].name)
        m.fail(item_key("probes", i) + ".name", "duplicate probe name '" + c.probes[i].name +
                                                    "' (also probes[" + std::to_string(j) +
                                                    "]); names must be distinct");
}

void check_min_widths(const CaseConfig& c, const MergedChecker& m) {
  const NumericsConfig& n = c.numerics;
  if (n.min_width_tip_m <= n.min_width_main_m) return;
  const std::string values = "min_width_tip " + format_number(n.min_width_tip_m) +
                             ", min_width_main " + format_number(n.min_width_main_m);
  if (m.present("numerics.min_width_tip") || !m.present("numerics.min_width_main"))
    m.fail("numerics.min_width_tip", "must be <= numerics.min_width_main (got " + values + ")");
  m.fail("numerics.min_width_main",
         "must be >= numerics.min_width_tip (got " + values +
             "; min_width_tip was not set and defaults to " +
             format_number(NumericsConfig{}.min_width_tip_m) + ")");
}

void check_ensemble(const CaseConfig& c, const MergedChecker& m) {
  if (!c.ensemble) return;
  const EnsembleConfig& e = *c.ensemble;
  if (c.load_ramp) m.fail("ensemble", "needs time stepping to time.end_time, not a load_ramp");
  if (e.map_every_s > c.time.end_time_s)
    m.fail(m.present("ensemble.map_every") ? "ensemble.map_every" : "time.end_time",
           "the maps are taken every ensemble.map_every, which must be <= time.end_time (got map_every " +
               format_number(e.map_every_s) + " s, end_time " + format_number(c.time.end_time_s) + " s)");
  const Rect& out = c.domain.outer;
  const double side = std::max(out.xmax - out.xmin, out.ymax - out.ymin);
  if (e.grid_cell_m > side)
    m.fail("ensemble.grid_cell", "must be at most the larger side of domain.outer (got " +
                                     format_number(e.grid_cell_m) + " m, side " + format_number(side) + " m)");
}

}  // namespace

const std::vector<CrossCheck>& cross_checks() {
  static const std::vector<CrossCheck> checks{
      {"`domain.inner` lies strictly inside `domain.outer`.", check_inner_inside_outer},
      {"`time.end_time` >= `time.dt`.", check_end_time},
      {"Without a `load_ramp`, `time.end_time` is a whole number of steps of `time.dt` (to "
       "1e-9 relative), at most 1e7 steps.",
       check_step_count},
      {"Lengths (`mesh.cell_size` of a structured mesh, `contact.vertex_vertex_activation`, `fractures[].segment_length`, "
       "`fractures[].initial_width`, `breakable_patterns[].cell_size`) are at most the larger side of "
       "`domain.outer`, the triangle areas of a Delaunay mesh at most its area, and the mesh has at most about 1e7 cells "
       "(the inner rectangle, or the domain, over the cell size squared or the largest triangle area).",
       check_lengths},
      {"`fractures[].segment_length` > 0 needs `mesh.type: delaunay` (a structured mesh makes a fracture of its cell "
       "edges) and is at least 0.01 of the mesh size it meets: the square root of `mesh.max_area_inner`, or of the "
       "larger of `max_area_inner` and `max_area_outer` when an end of the fracture lies outside `domain.inner` (the "
       "refinement cannot grade its triangles down to shorter pieces); its pieces count towards the 1e7 cells, two "
       "per piece.",
       check_segment_lengths},
      {"Without `far_field.in_situ`, a non-zero far-field stress needs a side to act on: `far_field.sides` is not "
       "empty, `sxx` needs `left` or `right` and `syy` needs `bottom` or `top` (the traction on a side is sigma . n); "
       "the same holds for the stress pattern and `sides` of `load_ramp`.",
       check_far_field_sides},
      {"`fractures[].pressure` acts on open joints: without `initially_open: true` on the same fracture, only on "
       "joints that break open during the run, so they must be breakable and some fracture initially open (a joint "
       "breaks only next to an open one, seed 2.3).",
       check_pressure_applies},
      {"A material with region `inner` or `outer` needs `domain.inner`; a material box "
       "overlaps `domain.outer`.",
       check_material_regions},
      {"`joints.breakable_region: inner` needs `domain.inner`.", check_breakable_region},
      {"`time.stop_when: fluid_at_edge` needs `domain.inner`, a `fluid` and no `load_ramp`.", check_stop_condition},
      {"`fluid.edge: vented` needs `domain.inner`.", check_vented_edge},
      {"With `contact.two_tier`, `contact.intact_stiffness_ratio` times the larger of `normal_stiffness` and "
       "`shear_stiffness` is at most 1e6.",
       check_intact_stiffness},
      {"`numerics.aperture_response: converged_contacts` needs `contact.method: alm` and a `numerics.flow_jacobian` "
       "of `dense` or `auto` (not `krylov` or `augmented`), and the iterated springs' stiffness factor (times `intact_stiffness_ratio` with `two_tier`) times 100 is at most 1e6.",
       check_aperture_response},
      {"Both ends of every fracture lie in `domain.outer` (its boundary included).",
       check_fractures_in_domain},
      {"Every point-load location, fixed point, injection point and probe lies in "
       "`domain.outer`.",
       check_points_in_domain},
      {"`injections`, `probes` and a fracture with `fluid_filled: true` need a `fluid` "
       "section.",
       check_fluid_needed},
      {"A `fluid` section needs at least one injection or one fracture with "
       "`fluid_filled: true`.",
       check_fluid_used},
      {"Probe names are distinct.", check_probe_names},
      {"`numerics.min_width_tip` <= `numerics.min_width_main`.", check_min_widths},
      {"`fracture.fracture_toughness` is required with `fracture.criterion: energy_release_rate`; it, "
       "`fracture.mode2_toughness` and `fracture.crack_closure` are only used with it.",
       check_fracture_criterion},
      {"`breakable_patterns` need `mesh.type: structured`; diagonal lines (`plus_45`, "
       "`minus_45`) need `mesh.split: four`.",
       check_pattern_mesh},
      {"The region and origin of every breakable pattern lie in `domain.outer` (its boundary "
       "included); its region holds at least one of its lines and at most 100000.",
       check_pattern_regions},
      {"`load_ramp`: levels as `start`/`increment`/`maximum` or as `history`, not both; a "
       "non-zero stress pattern; `stop_joints` exactly with `stop_when: broken_fraction`, each "
       "naming a fracture, breakable pattern or fracture set; no `fluid` section, no fracture `pressure` and no "
       "`time.end_time` with it.",
       check_load_ramp},
      {"`fracture_sets` need `mesh.type: delaunay`; `network_seed` needs a fracture set; set names are distinct and "
       "differ from the names of `fractures`, `fracture_maps` and `breakable_patterns`; a set's `length.min` (or "
       "`length.median`) is at most the diagonal of `domain.outer`.",
       check_fracture_sets},
      {"`random_seed` needs a key given as a distribution.", check_random_seed},
      {"`ensemble` needs time stepping (no `load_ramp`); `ensemble.map_every` <= `time.end_time`; "
       "`ensemble.grid_cell` at most the larger side of `domain.outer`.",
       check_ensemble}};
  return checks;
}

}  // namespace hfdda::io
