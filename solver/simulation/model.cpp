#include "simulation/model.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <limits>
#include <optional>
#include <unordered_map>
#include <numbers>
#include <sstream>

#include "core/errors.hpp"
#include "core/number_text.hpp"
#include "coupling/initial_opening.hpp"
#include "io/case_schema.hpp"
#include "simulation/model_flow.hpp"

namespace hfdda::simulation {

namespace {

using detail::domain_size;
using detail::format_point;

Vec2 block_centroid(const mesh::Mesh& m, const mesh::Block& block) {
  std::vector<Vec2> corners;
  for (int p : block.points) corners.push_back(m.points[p]);
  return polygon_moments(corners).centroid;
}

bool in_region(const io::MaterialConfig& zone, const io::CaseConfig& c, const Vec2& centroid) {
  if (zone.region == "all") return true;
  if (zone.region == "box") return zone.box.contains(centroid);
  const bool inside_inner = c.domain.inner && c.domain.inner->contains(centroid);
  return zone.region == "inner" ? inside_inner : !inside_inner;
}

void assign_materials(mesh::Mesh& m, const io::CaseConfig& c) {
  std::vector<int> blocks_per_zone(c.materials.size(), 0);
  for (auto& block : m.blocks) {
    const Vec2 centroid = block_centroid(m, block);
    block.material = 0;
    for (std::size_t z = 0; z < c.materials.size(); ++z)
      if (in_region(c.materials[z], c, centroid)) block.material = static_cast<int>(z);
  }
  for (const auto& block : m.blocks) ++blocks_per_zone[block.material];
  for (std::size_t z = 0; z < c.materials.size(); ++z)
    if (blocks_per_zone[z] == 0)
      throw InputError(c.file, c.materials[z].line, "materials[" + std::to_string(z) + "]",
                       "region '" + c.materials[z].region + "' contains no block of the mesh (empty region)");
}

/// joints.breakable_region: inner. A joint may break only if both of its blocks have
/// their centroid in domain.inner (joints on the inner boundary cannot).
void restrict_breaking_to_inner(mesh::Mesh& m, const io::CaseConfig& c) {
  auto inside = [&](int b) { return c.domain.inner->contains(block_centroid(m, m.blocks[b])); };
  for (auto& joint : m.joints)
    if (!inside(joint.block_a) || !inside(joint.block_b)) joint.properties.breakable = false;
}

mesh::JointProperties default_joint_properties(const io::CaseConfig& c) {
  mesh::JointProperties p;
  p.tensile_strength_Pa = c.joints.tensile_strength_Pa;
  p.fracture_toughness_Pa_sqrt_m = c.joints.fracture_toughness_Pa_sqrt_m;
  p.cohesion_Pa = c.joints.cohesion_Pa;
  p.friction_angle_rad = c.joints.friction_angle_deg * std::numbers::pi / 180.0;
  p.hydraulic_width_m = c.joints.hydraulic_width_m;
  p.breakable = c.joints.breakable;
  return p;
}

/// Joints by the grid cell of their midpoint, so that the joints along a fracture are
/// searched near it only (maps of tens of thousands of fractures).
class JointGrid {
 public:
  JointGrid(const mesh::Mesh& m, const Rect& outer) : outer_(outer) {
    cells_ = std::clamp(static_cast<int>(std::sqrt(static_cast<double>(m.joints.size()) / 4.0)), 1, 2048);
    bucket_.resize(static_cast<std::size_t>(cells_) * cells_);
    for (int j = 0; j < static_cast<int>(m.joints.size()); ++j) {
      const Vec2 mid = 0.5 * (m.points[m.joints[j].point_p] + m.points[m.joints[j].point_q]);
      bucket_[index(cell_x(mid.x()), cell_y(mid.y()))].push_back(j);
    }
  }
  /// Joints whose both ends lie within tol of segment [a, b].
  std::vector<int> on_segment(const mesh::Mesh& m, const Vec2& a, const Vec2& b, double tol) const {
    std::vector<int> ids;
    const double grow = tol;  // a joint on the segment has its midpoint within tol of it
    for (int ix = cell_x(std::min(a.x(), b.x()) - grow); ix <= cell_x(std::max(a.x(), b.x()) + grow); ++ix)
      for (int iy = cell_y(std::min(a.y(), b.y()) - grow); iy <= cell_y(std::max(a.y(), b.y()) + grow); ++iy)
        for (int j : bucket_[index(ix, iy)])
          if (point_segment_distance(m.points[m.joints[j].point_p], a, b) <= tol &&
              point_segment_distance(m.points[m.joints[j].point_q], a, b) <= tol)
            ids.push_back(j);
    std::sort(ids.begin(), ids.end());
    return ids;
  }

 private:
  int cell_x(double x) const { return std::clamp(static_cast<int>((x - outer_.xmin) / outer_.width() * cells_), 0, cells_ - 1); }
  int cell_y(double y) const { return std::clamp(static_cast<int>((y - outer_.ymin) / outer_.height() * cells_), 0, cells_ - 1); }
  std::size_t index(int ix, int iy) const { return static_cast<std::size_t>(ix) * cells_ + iy; }
  Rect outer_;
  int cells_ = 1;
  std::vector<std::vector<int>> bucket_;
};

/// The joints of each fracture. A Delaunay mesh knows which edges lie on which feature
/// (the constraint each edge was refined from; fracture f is constraint f), so a
/// snapped or split fracture is found exactly; a structured mesh is searched
/// geometrically. Either way a fracture must be made of joints, not outer-boundary edges.
std::vector<std::vector<int>> joints_of_fractures(const mesh::Mesh& m, const io::CaseConfig& c) {
  std::vector<std::vector<int>> joints(c.fractures.size());
  const auto edge_length = [&](int p, int q) { return (m.points[q] - m.points[p]).norm(); };
  const auto fail = [&](std::size_t f, double covered, double length, const std::string& why) {
    const io::FractureConfig& fr = c.fractures[f];
    std::ostringstream rule;
    rule << "fracture from " << format_point(fr.from) << " to " << format_point(fr.to)
         << " does not follow mesh edges (joints cover " << covered << " m of " << length << " m); " << why;
    throw InputError(c.file, fr.line, "fractures[" + std::to_string(f) + "]", rule.str());
  };
  if (m.has_feature_edges) {
    std::unordered_map<long long, int> joint_of_edge;
    const auto key = [&](int p, int q) {
      return static_cast<long long>(std::min(p, q)) * static_cast<long long>(m.points.size()) + std::max(p, q);
    };
    joint_of_edge.reserve(m.joints.size());
    for (int j = 0; j < static_cast<int>(m.joints.size()); ++j)
      joint_of_edge[key(m.joints[j].point_p, m.joints[j].point_q)] = j;
    std::vector<double> covered(c.fractures.size(), 0.0), total(c.fractures.size(), 0.0);
    for (const mesh::FeatureEdge& e : m.feature_edges) {
      const double length = edge_length(e.point_p, e.point_q);
      total[e.feature] += length;
      const auto it = joint_of_edge.find(key(e.point_p, e.point_q));
      if (it == joint_of_edge.end()) continue;
      joints[e.feature].push_back(it->second);
      covered[e.feature] += length;
    }
    for (std::size_t f = 0; f < c.fractures.size(); ++f) {
      if (joints[f].empty() || covered[f] < total[f])
        fail(f, covered[f], total[f], "part of it lies on the outer boundary of the domain");
      std::sort(joints[f].begin(), joints[f].end());
    }
    return joints;
  }
  const double tol = 1e-6 * domain_size(c);
  const JointGrid grid(m, c.domain.outer);
  for (std::size_t f = 0; f < c.fractures.size(); ++f) {
    const io::FractureConfig& fr = c.fractures[f];
    joints[f] = grid.on_segment(m, fr.from, fr.to, tol);
    double covered = 0.0;
    for (int j : joints[f]) covered += edge_length(m.joints[j].point_p, m.joints[j].point_q);
    const double length = (fr.to - fr.from).norm();
    if (std::abs(covered - length) > 1e-6 * length)
      fail(f, covered, length, "on a structured mesh a fracture must lie on grid lines");
  }
  return joints;
}

// --- Joint properties drawn joint by joint (seed 5.5) ------------------------

/// The joint properties a case may give as distributions.
enum JointProperty { kTensileStrength, kFrictionAngle, kHydraulicWidth, kJointProperties };

/// A key given as a distribution that applies to joints: of `joints`, a fracture or a set.
struct JointLaw {
  std::string key;
  stochastic::ScalarDistribution law;
};

/// Per property, the index into JointLaws of the key that set a joint's value last;
/// -1: a number.
using JointLawChoice = std::array<int, kJointProperties>;

class JointLaws {
 public:
  /// Registers the law of `key`; returns its index, or -1 when the key holds a number.
  int add(const std::string& key, const io::ParameterLaw& law) {
    if (!law) return -1;
    laws_.push_back({key, *law});
    return static_cast<int>(laws_.size()) - 1;
  }
  /// The laws of the three properties of `prefix` ("joints", "fractures[2]").
  JointLawChoice add_all(const std::string& prefix, const io::ParameterLaw& tensile_strength,
                         const io::ParameterLaw& friction_angle, const io::ParameterLaw& hydraulic_width) {
    return {add(prefix + ".tensile_strength", tensile_strength), add(prefix + ".friction_angle", friction_angle),
            add(prefix + ".hydraulic_width", hydraulic_width)};
  }
  const JointLaw& operator[](int i) const { return laws_[static_cast<std::size_t>(i)]; }

 private:
  std::vector<JointLaw> laws_;
};

/// Which law each joint's properties come from, set as `joints` and the fractures apply.
struct JointLawMap {
  JointLaws laws;
  std::vector<JointLawChoice> of_joint;
};

/// Draws the properties whose last key was a distribution, joint by joint in joint order.
/// A joint whose T0 follows from a fracture toughness (seed eq. 4.13) draws no T0.
void draw_joint_properties(mesh::Mesh& m, const JointLawMap& map, ParameterSampler& sampler) {
  for (std::size_t j = 0; j < m.joints.size(); ++j) {
    mesh::JointProperties& p = m.joints[j].properties;
    const JointLawChoice& choice = map.of_joint[j];
    const auto draw = [&](int property) {
      const JointLaw& l = map.laws[choice[property]];
      return sampler.draw(l.key, l.law, "joint");
    };
    if (choice[kTensileStrength] >= 0 && !p.fracture_toughness_Pa_sqrt_m)
      p.tensile_strength_Pa = draw(kTensileStrength);
    if (choice[kFrictionAngle] >= 0) p.friction_angle_rad = draw(kFrictionAngle) * std::numbers::pi / 180.0;
    if (choice[kHydraulicWidth] >= 0) p.hydraulic_width_m = draw(kHydraulicWidth);
  }
}

/// What a fracture sets on its joints; unset values leave the joint's as they are.
struct JointOverrides {
  bool initially_open = false;
  bool natural = false;
  std::optional<bool> breakable;
  std::optional<double> tensile_strength_Pa, fracture_toughness_Pa_sqrt_m, cohesion_Pa, friction_angle_deg,
      hydraulic_width_m, pressure_Pa;
  JointLawChoice laws{-1, -1, -1};  ///< of the values above given as distributions
};

void apply_overrides(mesh::JointProperties& p, JointLawChoice& choice, const JointOverrides& o) {
  p.initially_open = p.initially_open || o.initially_open;
  p.natural = p.natural || o.natural;
  if (o.breakable) p.breakable = *o.breakable;
  // The fracture's own choice of T0 or K_IC wins over the one of `joints` (or of an earlier fracture).
  if (o.tensile_strength_Pa) {
    p.tensile_strength_Pa = *o.tensile_strength_Pa;
    p.fracture_toughness_Pa_sqrt_m.reset();
    choice[kTensileStrength] = o.laws[kTensileStrength];
  }
  if (o.fracture_toughness_Pa_sqrt_m) p.fracture_toughness_Pa_sqrt_m = o.fracture_toughness_Pa_sqrt_m;
  if (o.cohesion_Pa) p.cohesion_Pa = *o.cohesion_Pa;
  if (o.friction_angle_deg) {
    p.friction_angle_rad = *o.friction_angle_deg * std::numbers::pi / 180.0;
    choice[kFrictionAngle] = o.laws[kFrictionAngle];
  }
  if (o.hydraulic_width_m) {
    p.hydraulic_width_m = *o.hydraulic_width_m;
    choice[kHydraulicWidth] = o.laws[kHydraulicWidth];
  }
  if (o.pressure_Pa) p.prescribed_pressure_Pa = *o.pressure_Pa;
}

JointOverrides overrides_of(const io::FractureConfig& fr, const std::string& key, JointLaws& laws) {
  return {fr.initially_open,
          fr.natural,
          fr.breakable,
          fr.tensile_strength_Pa,
          fr.fracture_toughness_Pa_sqrt_m,
          fr.cohesion_Pa,
          fr.friction_angle_deg,
          fr.hydraulic_width_m,
          fr.pressure_Pa,
          laws.add_all(key, fr.tensile_strength_law, fr.friction_angle_law, fr.hydraulic_width_law)};
}

/// A generated fracture is a natural fracture with its set's values (seed Table 5.3).
JointOverrides overrides_of(const io::FractureSetConfig& set, const std::string& key, JointLaws& laws) {
  JointOverrides o;
  o.natural = true;
  o.tensile_strength_Pa = set.tensile_strength_Pa;
  o.cohesion_Pa = set.cohesion_Pa;
  o.friction_angle_deg = set.friction_angle_deg;
  o.hydraulic_width_m = set.hydraulic_width_m;
  o.laws = laws.add_all(key, set.tensile_strength_law, set.friction_angle_law, set.hydraulic_width_law);
  return o;
}

/// Joints along each fracture take its overrides; a fracture must be made of joints.
std::vector<int> apply_fractures(mesh::Mesh& m, const io::CaseConfig& c, JointLawMap& law_map) {
  std::vector<int> fracture_of_joint(m.joints.size(), -1);
  const std::vector<std::vector<int>> joints = joints_of_fractures(m, c);
  for (std::size_t f = 0; f < c.fractures.size(); ++f) {
    const JointOverrides overrides = overrides_of(c.fractures[f], "fractures[" + std::to_string(f) + "]", law_map.laws);
    for (int j : joints[f]) {
      fracture_of_joint[j] = static_cast<int>(f);
      apply_overrides(m.joints[j].properties, law_map.of_joint[j], overrides);
    }
  }
  return fracture_of_joint;
}

/// The network of the case's fracture sets on the joints no written fracture holds, its
/// sets' values applied to its joints; appended to `fractures` and `fracture_of_joint`.
networks::FractureNetwork apply_fracture_sets(mesh::Mesh& m, const io::CaseConfig& c,
                                              std::vector<ModelFracture>& fractures,
                                              std::vector<int>& fracture_of_joint, JointLawMap& law_map) {
  if (c.fracture_sets.empty()) return {};
  if (c.mesh.kind != io::MeshKind::delaunay)  // refused by the case checks already
    throw InputError(c.file, c.fracture_sets.front().line, "fracture_sets", "needs mesh.type: delaunay");
  std::vector<char> reserved(m.joints.size(), 0);
  for (std::size_t j = 0; j < m.joints.size(); ++j) reserved[j] = fracture_of_joint[j] >= 0;
  networks::FractureNetwork network;
  try {
    network = networks::generate_fracture_network(m, fracture_set_settings(c),
                                                  static_cast<std::uint64_t>(c.network_seed), reserved);
  } catch (const ModelError& e) {
    throw InputError(c.file, c.fracture_sets.front().line, "fracture_sets", e.what());
  }
  std::vector<JointOverrides> set_overrides;
  for (std::size_t s = 0; s < c.fracture_sets.size(); ++s)
    set_overrides.push_back(overrides_of(c.fracture_sets[s], "fracture_sets[" + std::to_string(s) + "]", law_map.laws));
  const int first = static_cast<int>(fractures.size());
  for (std::size_t n = 0; n < network.fractures.size(); ++n) {
    const networks::GeneratedFracture& g = network.fractures[n];
    fractures.push_back({g.name, -1, g.set});
    for (int j : g.joints) {
      fracture_of_joint[j] = first + static_cast<int>(n);
      apply_overrides(m.joints[j].properties, law_map.of_joint[j], set_overrides[g.set]);
    }
  }
  return network;
}

/// Boundary edges on one side of the outer rectangle.
bool edge_on_side(const mesh::Mesh& m, const mesh::BoundaryEdge& e, const Rect& outer, const std::string& side,
                  double tol) {
  const Vec2& p = m.points[e.point_p];
  const Vec2& q = m.points[e.point_q];
  if (side == "left") return std::abs(p.x() - outer.xmin) < tol && std::abs(q.x() - outer.xmin) < tol;
  if (side == "right") return std::abs(p.x() - outer.xmax) < tol && std::abs(q.x() - outer.xmax) < tol;
  if (side == "bottom") return std::abs(p.y() - outer.ymin) < tol && std::abs(q.y() - outer.ymin) < tol;
  return std::abs(p.y() - outer.ymax) < tol && std::abs(q.y() - outer.ymax) < tol;  // top
}

/// Outer and optional inner rectangle: shared by both mesh specifications.
template <class Spec>
void set_domain(Spec& spec, const io::CaseConfig& c) {
  spec.outer = c.domain.outer;
  spec.has_inner = c.domain.inner.has_value();
  if (spec.has_inner) spec.inner = *c.domain.inner;
}

/// The materials of the block system: one per zone of the case, then, for each block of a
/// zone whose Young's modulus or Poisson's ratio is a distribution, one of its own with
/// the values drawn for it (seed 5.5: the rock blocks' E and nu are triangular laws),
/// blocks in order. Points such blocks at their material; `zone_of_material` gets the
/// zone of every material.
std::vector<dda::Material> block_materials(mesh::Mesh& m, const io::CaseConfig& c, ParameterSampler& sampler,
                                          std::vector<int>& zone_of_material) {
  std::vector<dda::Material> materials;
  zone_of_material.clear();
  for (std::size_t z = 0; z < c.materials.size(); ++z) {
    const io::MaterialConfig& mc = c.materials[z];
    materials.push_back({mc.youngs_modulus_Pa, mc.poissons_ratio, mc.density_kg_m3});
    zone_of_material.push_back(static_cast<int>(z));
  }
  for (mesh::Block& block : m.blocks) {
    const int z = block.material;
    const io::MaterialConfig& mc = c.materials[static_cast<std::size_t>(z)];
    if (!mc.youngs_modulus_law && !mc.poissons_ratio_law) continue;
    const std::string zone = "materials[" + std::to_string(z) + "]";
    dda::Material own = materials[static_cast<std::size_t>(z)];
    if (mc.youngs_modulus_law)
      own.youngs_modulus_Pa = sampler.draw(zone + ".youngs_modulus", *mc.youngs_modulus_law, "block");
    if (mc.poissons_ratio_law)
      own.poissons_ratio = sampler.draw(zone + ".poissons_ratio", *mc.poissons_ratio_law, "block");
    block.material = static_cast<int>(materials.size());
    materials.push_back(own);
    zone_of_material.push_back(z);
  }
  return materials;
}

}  // namespace

mesh::Mesh build_case_mesh(const io::CaseConfig& c) {
  const std::string& mesh_file = c.mesh_file.empty() ? c.file : c.mesh_file;
  mesh::Mesh m;
  try {
    if (c.mesh.kind == io::MeshKind::structured) {
      mesh::StructuredMeshSpec spec;
      set_domain(spec, c);
      spec.cell_size_m = c.mesh.cell_size_m;
      spec.outer_growth = c.mesh.outer_growth;
      spec.split = c.mesh.split;
      m = mesh::build_structured_mesh(spec);
    } else {
      mesh::DelaunayMeshSpec spec;
      set_domain(spec, c);
      spec.max_area_inner_m2 = c.mesh.max_area_inner_m2;
      // Without an inner rectangle, max_area_inner bounds the whole domain (docs/case_file.md).
      spec.max_area_outer_m2 = c.domain.inner ? c.mesh.max_area_outer_m2 : c.mesh.max_area_inner_m2;
      spec.min_angle_deg = c.mesh.min_angle_deg;
      spec.snap_tolerance_m = c.mesh.snap_tolerance_m;
      for (const auto& f : c.fractures) spec.constraints.push_back({f.name, f.from, f.to, f.segment_length_m});
      m = mesh::build_delaunay_mesh(spec);
    }
    mesh::build_topology(m, default_joint_properties(c));
    if (c.joints.breakable_region == "inner") restrict_breaking_to_inner(m, c);
  } catch (const ModelError& e) {
    throw InputError(mesh_file, c.mesh.line, "mesh", e.what());
  }
  return m;
}

std::string fracture_adjustments_note(const io::CaseConfig& c, const mesh::Mesh& m) {
  std::string note;
  const io::FractureConfig* longest_cut = nullptr;
  int cut = 0;
  for (const io::FractureConfig& f : c.fractures)
    if (f.clipped_length_m > 0.0) {
      ++cut;
      if (!longest_cut || f.clipped_length_m > longest_cut->clipped_length_m) longest_cut = &f;
    }
  if (cut > 0)
    note += std::to_string(cut) + " fracture-map row(s) cut at domain.outer (longest cut " +
            number_text(longest_cut->clipped_length_m) + " m, " + longest_cut->name + ")";
  if (!m.feature_snaps.empty()) {
    const auto largest = std::max_element(m.feature_snaps.begin(), m.feature_snaps.end(),
                                          [](const auto& a, const auto& b) { return a.moved_m < b.moved_m; });
    if (!note.empty()) note += "; ";
    note += std::to_string(m.feature_snaps.size()) + " fracture end(s) snapped onto another fracture or the " +
            "domain's side within " + number_text(m.feature_snap_tolerance_m) + " m (largest move " +
            number_text(largest->moved_m) + " m, " + largest->feature + ")";
  }
  return note;
}

std::string initial_opening_note(const Model& model) {
  if (!model.initial_opening) return "";
  const InitialOpeningSummary& s = *model.initial_opening;
  std::string note = "initial_opening: elastic: " + std::to_string(s.steps) + " step(s) before t = 0";
  if (!std::isnan(s.last_relative_change)) {
    char change[32];
    std::snprintf(change, sizeof change, "%.2g", s.last_relative_change);
    note += std::string(", the last changing an aperture by at most ") + change + " of it";
  }
  if (s.settled) return note + " (settled)";
  note += s.growing ? "; not settled: the changes grew, so the last step was taken back"
                    : "; not settled within " + std::to_string(coupling::kMaxSettlingSteps) + " steps";
  return note + " (the first steps may squeeze fluid out; docs/design_notes.md section 31)";
}

std::vector<networks::FractureSetSettings> fracture_set_settings(const io::CaseConfig& c) {
  std::vector<networks::FractureSetSettings> sets;
  for (const io::FractureSetConfig& fs : c.fracture_sets) {
    networks::FractureSetSettings s;
    s.name = fs.name;
    s.azimuth_deg = fs.azimuth_deg;
    s.azimuth_tolerance_deg = fs.azimuth_tolerance_deg;
    s.growth_tolerance_deg = fs.growth_tolerance_deg;
    s.seed_fraction = fs.seed_fraction;
    const io::FractureLengthConfig& l = fs.length;
    using D = networks::LengthDistribution;
    s.length.distribution = l.distribution == "triangular" ? D::triangular
                            : l.distribution == "lognormal" ? D::lognormal
                            : l.distribution == "power_law" ? D::power_law
                                                            : D::uniform;
    s.length.min_m = l.min_m.value_or(0.0);
    s.length.max_m = l.max_m.value_or(0.0);
    s.length.mode_m = l.mode_m.value_or(0.0);
    s.length.median_m = l.median_m.value_or(0.0);
    s.length.sigma = l.sigma.value_or(0.0);
    s.length.exponent = l.exponent.value_or(0.0);
    sets.push_back(std::move(s));
  }
  return sets;
}

FracturedMesh build_fractured_mesh(const io::CaseConfig& c, ParameterSampler& sampler) {
  FracturedMesh out;
  out.mesh = build_case_mesh(c);
  assign_materials(out.mesh, c);
  // Every joint starts with the values of `joints`; fractures, then sets, override them.
  JointLawMap law_map;
  law_map.of_joint.assign(out.mesh.joints.size(),
                          law_map.laws.add_all("joints", c.joints.tensile_strength_law, c.joints.friction_angle_law,
                                               c.joints.hydraulic_width_law));
  out.fracture_of_joint = apply_fractures(out.mesh, c, law_map);
  for (std::size_t f = 0; f < c.fractures.size(); ++f)
    out.fractures.push_back({c.fractures[f].name, static_cast<int>(f), -1});
  out.network = apply_fracture_sets(out.mesh, c, out.fractures, out.fracture_of_joint, law_map);
  draw_joint_properties(out.mesh, law_map, sampler);
  return out;
}

FracturedMesh build_fractured_mesh(const io::CaseConfig& c) {
  ParameterSampler sampler(static_cast<std::uint64_t>(c.random_seed));
  return build_fractured_mesh(c, sampler);
}

dda::MechanicsSettings mechanics_settings(const io::CaseConfig& c) {
  double max_modulus = 0.0;
  for (const auto& m : c.materials)
    max_modulus = std::max(max_modulus, m.youngs_modulus_law ? m.youngs_modulus_law->highest() : m.youngs_modulus_Pa);
  dda::MechanicsSettings s;
  s.augmented_lagrangian = c.contact.method == io::ContactMethod::augmented_lagrangian;
  s.two_tier_contacts = c.contact.two_tier;
  s.intact_stiffness_ratio = c.contact.intact_stiffness_ratio;
  if (c.numerics.aperture_response == io::ApertureResponse::converged_contacts)
    s.converged_response_stiffening = io::schema::kConvergedResponseStiffening;
  s.lumped_fluid_load = c.numerics.fluid_load == io::FluidLoad::lumped;
  s.normal_stiffness_N_m = c.contact.normal_stiffness_factor * max_modulus;
  s.shear_stiffness_N_m = c.contact.shear_stiffness_factor * max_modulus;
  s.fixed_point_stiffness_N_m = c.contact.fixed_point_stiffness_factor * max_modulus;
  s.vertex_vertex_activation_m = c.contact.vertex_vertex_activation_m;
  s.alm_force_tolerance = c.numerics.alm_force_tolerance;
  s.max_alm_iterations = c.numerics.max_alm_iterations;
  s.max_open_close_iterations = c.numerics.max_open_close_iterations;
  s.max_state_flips = c.numerics.max_state_flips;
  s.close_penetrating_cycles = c.numerics.cycle_resolution == io::CycleResolution::close_penetrating;
  s.relock_in_failure_step = c.numerics.relock_in_failure_step;
  s.friction_at_solution = c.numerics.friction_at_solution;
  s.dynamic = c.numerics.analysis == io::AnalysisKind::dynamic_analysis;
  s.mechanism_inertia_time_s = c.numerics.mechanism_inertia_time_s;
  s.low_rank_updates = c.numerics.low_rank_updates;
  return s;
}

fracture::FractureRules fracture_rules(const io::CaseConfig& c) {
  fracture::FractureRules r;
  r.tie_tolerance = c.numerics.tie_tolerance;
  r.shear_failure_of_intact_joints = c.numerics.shear_failure_of_intact_joints;
  r.failure_needs_open_neighbour_and_fluid = !c.load_ramp.has_value();
  r.failures_on_settled_contacts = c.numerics.failures_on_settled_contacts;
  if (c.fracture.criterion == io::FailureCriterionKind::energy_release_rate) {
    r.criterion = fracture::FailureCriterion::energy_release_rate;
    r.toughness.mode1_Pa_sqrt_m = *c.fracture.fracture_toughness_Pa_sqrt_m;
    r.toughness.mode2_Pa_sqrt_m = c.fracture.mode2_toughness_Pa_sqrt_m.value_or(r.toughness.mode1_Pa_sqrt_m);
    r.toughness.closure = c.fracture.crack_closure == io::CrackClosureKind::extrapolated
                              ? fracture::CrackClosure::extrapolated
                              : fracture::CrackClosure::one_joint;
  }
  return r;
}

Model build_model(const io::CaseConfig& case_config) {
  ParameterSampler sampler(static_cast<std::uint64_t>(case_config.random_seed));
  return build_model(case_config, sampler);
}

Model build_model(const io::CaseConfig& case_config, ParameterSampler& sampler) {
  const auto start = std::chrono::steady_clock::now();
  Model model;
  model.config = draw_run_parameters(case_config, sampler);
  const io::CaseConfig& c = model.config;
  FracturedMesh fractured = build_fractured_mesh(c, sampler);
  mesh::Mesh& m = fractured.mesh;
  model.fractures = std::move(fractured.fractures);
  model.fracture_of_joint = std::move(fractured.fracture_of_joint);
  model.network = std::move(fractured.network);

  std::vector<dda::Material> materials = block_materials(m, c, sampler, model.zone_of_material);
  model.parameter_draws = sampler.draws();
  model.system = std::make_unique<dda::BlockSystem>(m, std::move(materials), mechanics_settings(c));
  dda::BlockSystem& system = *model.system;

  for (const auto& fp : c.fixed_points) system.add_fixed_point(fp.at);
  for (const auto& pl : c.point_loads) system.add_point_load(pl.at, pl.force_N_per_m);
  system.set_body_force(c.body_force_N_m3);

  Eigen::Matrix2d far_field;
  far_field << c.far_field.sxx_Pa, c.far_field.sxy_Pa, c.far_field.sxy_Pa, c.far_field.syy_Pa;
  if (far_field.norm() > 0.0) {
    const double tol = 1e-9 * domain_size(c);
    static const std::vector<std::string> all_sides{"left", "right", "bottom", "top"};
    const auto& sides = c.far_field.in_situ ? all_sides : c.far_field.sides;
    for (int e = 0; e < static_cast<int>(m.boundary_edges.size()); ++e)
      for (const std::string& side : sides)
        if (edge_on_side(m, m.boundary_edges[e], c.domain.outer, side, tol)) system.add_boundary_stress(e, far_field);
    if (c.far_field.in_situ) system.set_in_situ_stress(far_field);
  }
  if (c.load_ramp) {
    const io::LoadRampConfig& ramp = *c.load_ramp;
    Eigen::Matrix2d pattern;
    pattern << ramp.sxx, ramp.sxy, ramp.sxy, ramp.syy;
    const double tol = 1e-9 * domain_size(c);
    for (int e = 0; e < static_cast<int>(m.boundary_edges.size()); ++e)
      for (const std::string& side : ramp.sides)
        if (edge_on_side(m, m.boundary_edges[e], c.domain.outer, side, tol)) system.add_ramped_boundary_stress(e, pattern);
  }

  // Prescribed fluid pressure: on both faces of the fracture's joints and at their points.
  std::vector<coupling::FluidLoadModel*> fluids;
  auto prescribed = coupling::PrescribedPressure::from_joint_properties(system.mesh());
  if (prescribed.any_wetted()) {
    model.prescribed = std::make_unique<coupling::PrescribedPressure>(std::move(prescribed));
    fluids.push_back(model.prescribed.get());
  }
  if (c.fluid) {
    const detail::InitialFill fill = detail::build_flow_network(model, c);
    fluids.push_back(model.coupling.get());
    if (!fill.opened_by_fluid.empty()) detail::open_by_initial_pressure(model, fill);
  }
  model.step = std::make_unique<coupling::CoupledStep>(system, std::move(fluids), fracture_rules(c));
  if (c.load_ramp) {
    std::vector<std::string> names;
    for (const ModelFracture& f : model.fractures) names.push_back(f.name);
    model.ramp = std::make_unique<LoadRamp>(c, system, model.fracture_of_joint, names, model.step->bonds(),
                                            fracture_rules(c));
  }
  model.mesh_seconds_ms = static_cast<int>(
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  return model;
}

}  // namespace hfdda::simulation
