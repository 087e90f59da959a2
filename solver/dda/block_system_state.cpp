// Checkpoint state of the block system: what the next step depends on. The per-step
// terms (block matrices, loads, linearisations, ALM corrections) are rebuilt by
// begin_step() and are not stored.

#include <cstdint>

#include "core/binary_io.hpp"
#include "dda/block_system.hpp"

namespace hfdda::dda {

namespace {

void put_spring(BinaryWriter& out, const VertexEdgeSpring& s) {
  for (int v : {s.vertex_block, s.vertex_corner, s.edge_block, s.edge_corner, s.slot}) out.put(v);
  for (double v : {s.reference_ratio, s.normal_multiplier_N, s.shear_multiplier_N, s.gap0, s.shear0, s.edge_length_m})
    out.put(v);
  out.put_matrix(s.gap_vertex);
  out.put_matrix(s.gap_edge);
  out.put_matrix(s.shear_vertex);
  out.put_matrix(s.shear_edge);
}

void get_spring(BinaryReader& in, VertexEdgeSpring& s) {
  for (int* v : {&s.vertex_block, &s.vertex_corner, &s.edge_block, &s.edge_corner, &s.slot}) in.get(*v);
  for (double* v : {&s.reference_ratio, &s.normal_multiplier_N, &s.shear_multiplier_N, &s.gap0, &s.shear0,
                    &s.edge_length_m})
    in.get(*v);
  in.get_matrix(s.gap_vertex);
  in.get_matrix(s.gap_edge);
  in.get_matrix(s.shear_vertex);
  in.get_matrix(s.shear_edge);
}

void put_attachments(BinaryWriter& out, const std::vector<ExternalLoads::PointAttachment>& list) {
  out.put<std::uint64_t>(list.size());
  for (const auto& a : list) {
    out.put(a.block);
    out.put_matrix(a.position);
    out.put_matrix(a.anchor);
    out.put_matrix(a.force_N);
  }
}

void get_attachments(BinaryReader& in, std::vector<ExternalLoads::PointAttachment>& list) {
  in.expect<std::uint64_t>(list.size(), "fixed points or point loads");
  for (auto& a : list) {
    in.get(a.block);
    in.get_matrix(a.position);
    in.get_matrix(a.anchor);
    in.get_matrix(a.force_N);
  }
}

}  // namespace

void ContactSet::save_state(BinaryWriter& out) const {
  out.put<std::uint64_t>(contacts_.size());
  for (const Contact& c : contacts_) {
    for (int v : {c.joint, c.end, c.point, c.n_springs, c.block_a, c.corner_a, c.block_c, c.corner_c}) out.put(v);
    for (const VertexEdgeSpring& s : c.springs) put_spring(out, s);
    for (double v : {c.length_m, c.cohesion_Pa, c.tan_friction, c.friction_sign}) out.put(v);
    out.put(c.state);
    for (bool v : {c.bonded, c.vertex_vertex_active, c.ever_active}) out.put(v);
  }
  std::vector<int> pairs;
  for (const auto& [a, c] : couplings_) pairs.insert(pairs.end(), {a, c});
  out.put_vector(pairs);
}

void ContactSet::restore_state(BinaryReader& in) {
  in.expect<std::uint64_t>(contacts_.size(), "number of contacts");
  for (Contact& c : contacts_) {
    for (int* v : {&c.joint, &c.end, &c.point, &c.n_springs, &c.block_a, &c.corner_a, &c.block_c, &c.corner_c})
      in.get(*v);
    for (VertexEdgeSpring& s : c.springs) get_spring(in, s);
    for (double* v : {&c.length_m, &c.cohesion_Pa, &c.tan_friction, &c.friction_sign}) in.get(*v);
    in.get(c.state);
    for (bool* v : {&c.bonded, &c.vertex_vertex_active, &c.ever_active}) in.get(*v);
  }
  std::vector<int> pairs;
  in.get_vector(pairs);
  if (pairs.size() % 2 != 0) throw std::runtime_error("checkpoint data: odd block-pair list");
  couplings_.clear();
  for (std::size_t i = 0; i < pairs.size(); i += 2) couplings_.emplace_back(pairs[i], pairs[i + 1]);
  pattern_changed_ = true;
}

void BlockSystem::save_state(BinaryWriter& out) const {
  out.put<std::int64_t>(n_blocks());
  out.put_matrices(blocks_.corners);
  out.put_matrices(blocks_.stress);
  out.put_matrices(blocks_.velocity);
  out.put_matrices(blocks_.last_d);
  put_attachments(out, loads_.fixed_points);
  put_attachments(out, loads_.point_loads);
  out.put(loads_.ramp_level_Pa);
  contacts_.save_state(out);
  out.put(total_vv_activations_);
}

void BlockSystem::restore_state(BinaryReader& in) {
  in.expect<std::int64_t>(n_blocks(), "number of blocks");
  const std::size_t n_corners = blocks_.corners.size();
  in.get_matrices(blocks_.corners);
  in.get_matrices(blocks_.stress);
  in.get_matrices(blocks_.velocity);
  in.get_matrices(blocks_.last_d);
  if (blocks_.corners.size() != n_corners || blocks_.stress.size() != blocks_.material.size() ||
      blocks_.velocity.size() != blocks_.material.size() || blocks_.last_d.size() != blocks_.material.size())
    throw std::runtime_error("checkpoint does not match the model: block fields");
  get_attachments(in, loads_.fixed_points);
  get_attachments(in, loads_.point_loads);
  in.get(loads_.ramp_level_Pa);
  contacts_.restore_state(in);
  in.get(total_vv_activations_);
  // K's pattern from the stored block pairs (the vertex-vertex pairs activated so far),
  // in their order, so the springs' slots and the factorisation are those of the run.
  rebuild_pattern();
}

}  // namespace hfdda::dda
