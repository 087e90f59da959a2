// ContactSet's step snapshot: roll_back() restores every contact changed in the step,
// joint contacts and vertex-vertex contacts alike, although only the joint contacts,
// the active vertex-vertex contacts and the candidates passed to remember() are copied.

#include <gtest/gtest.h>

#include <vector>

#include "dda/contact_set.hpp"
#include "mesh/mesh.hpp"

namespace hfdda::dda {
namespace {

mesh::Mesh four_triangles_per_cell(int nx, int ny) {
  mesh::StructuredMeshSpec spec;
  spec.outer = Rect{0.0, 1.0 * nx, 0.0, 1.0 * ny};
  spec.cell_size_m = 1.0;
  spec.split = mesh::CellSplit::four;
  mesh::Mesh m = mesh::build_structured_mesh(spec);
  mesh::build_topology(m, mesh::JointProperties{});
  return m;
}

void expect_same(const Contact& a, const Contact& b, int ci) {
  SCOPED_TRACE("contact " + std::to_string(ci));
  EXPECT_EQ(a.state, b.state);
  EXPECT_EQ(a.bonded, b.bonded);
  EXPECT_EQ(a.vertex_vertex_active, b.vertex_vertex_active);
  EXPECT_EQ(a.ever_active, b.ever_active);
  EXPECT_EQ(a.friction_sign, b.friction_sign);
  for (int k = 0; k < 2; ++k) {
    EXPECT_EQ(a.springs[k].normal_multiplier_N, b.springs[k].normal_multiplier_N);
    EXPECT_EQ(a.springs[k].vertex_block, b.springs[k].vertex_block);
    EXPECT_EQ(a.springs[k].gap0, b.springs[k].gap0);
  }
}

void expect_all_same(const ContactSet& set, const std::vector<Contact>& before) {
  ASSERT_EQ(set.size(), static_cast<int>(before.size()));
  for (int ci = 0; ci < set.size(); ++ci) expect_same(set[ci], before[ci], ci);
}

/// What an activation does to a candidate (BlockSystem::apply_change).
void activate(Contact& c) {
  c.vertex_vertex_active = true;
  c.ever_active = true;
  c.state = ContactState::sliding;
  c.springs[0].vertex_block = c.block_a;
  c.springs[0].normal_multiplier_N = -5.0;
  c.springs[0].gap0 = 1e-3;
}

TEST(ContactSetSnapshot, RollBackRestoresJointsAndRememberedCandidates) {
  const mesh::Mesh m = four_triangles_per_cell(3, 2);
  ContactSet set(m);
  const int first_candidate = set.n_joint_contacts();
  ASSERT_GT(set.size(), first_candidate + 2) << "the mesh has vertex-vertex candidates";
  const std::vector<Contact> before = set.all();

  set.begin_step();
  set[0].state = ContactState::open;
  set[0].bonded = false;
  set[1].springs[1].normal_multiplier_N = 42.0;
  set.remember(first_candidate + 1);
  activate(set[first_candidate + 1]);
  set.remember(first_candidate + 1);  // a second call keeps the first copy
  set[first_candidate + 1].springs[0].normal_multiplier_N = -7.0;
  set.roll_back();
  expect_all_same(set, before);
}

TEST(ContactSetSnapshot, ActiveCandidatesAreKeptWithoutRemember) {
  const mesh::Mesh m = four_triangles_per_cell(2, 2);
  ContactSet set(m);
  const int candidate = set.n_joint_contacts();
  set.begin_step();
  set.remember(candidate);
  activate(set[candidate]);  // active at the end of this step...
  const std::vector<Contact> step_two_start = set.all();

  set.begin_step();  // ...so the next step copies it at its start
  set[candidate].springs[0].normal_multiplier_N = 3.0;  // an ALM update, no remember()
  set[candidate].state = ContactState::open;
  set[candidate].vertex_vertex_active = false;
  set.roll_back();
  expect_all_same(set, step_two_start);
}

TEST(ContactSetSnapshot, ANewStepForgetsThePreviousOne) {
  const mesh::Mesh m = four_triangles_per_cell(2, 1);
  ContactSet set(m);
  const int candidate = set.n_joint_contacts();
  set.begin_step();
  set.remember(candidate);
  activate(set[candidate]);
  set.begin_step();  // the activation is now part of the step's start
  set[candidate].springs[0].normal_multiplier_N = 9.0;
  set.roll_back();
  EXPECT_TRUE(set[candidate].vertex_vertex_active);
  EXPECT_EQ(set[candidate].springs[0].normal_multiplier_N, -5.0);
}

}  // namespace
}  // namespace hfdda::dda
