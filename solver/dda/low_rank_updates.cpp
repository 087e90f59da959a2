// Low-rank changes of K within a step (MechanicsSettings::low_rank_updates). The block
// terms and the spring linearisations are fixed for the step (seed 2.3), so a change of
// contact states between two open-close iterations adds or removes penalty springs
// k e e^T (e: 12 entries on two blocks) and nothing else, unless the mechanism holds
// change too. Those springs are applied to the step's factorisation of K through
// SpdSolver::modify (Woodbury identity) instead of a new factorisation
// (docs/design_notes.md section 26).

#include <cmath>

#include "dda/block_system.hpp"

namespace hfdda::dda {

BlockSystem::ContactTerms BlockSystem::contact_terms(const Contact& c) const {
  ContactTerms terms;
  if (c.state == ContactState::open) return terms;
  const double kn = normal_stiffness(c), ks = shear_stiffness(c);
  const double w = 1.0 / c.n_springs;
  for (int k = 0; k < c.n_springs; ++k) {
    const auto& s = c.springs[k];
    terms.term[2 * k] = {s.vertex_block, s.edge_block, s.gap_vertex, s.gap_edge, w * kn};
    terms.present[2 * k] = true;
    if (c.state == ContactState::locked) {
      terms.term[2 * k + 1] = {s.vertex_block, s.edge_block, s.shear_vertex, s.shear_edge, w * ks};
      terms.present[2 * k + 1] = true;
    }
  }
  return terms;
}

void BlockSystem::remember_factorised_terms(int ci) {
  if (!settings_.low_rank_updates || !factor_of_this_step_) return;
  if (terms_remembered_.size() != contacts_.all().size()) terms_remembered_.assign(contacts_.all().size(), 0);
  if (terms_remembered_[ci]) return;
  terms_remembered_[ci] = 1;
  factorised_terms_.emplace_back(ci, contact_terms(contacts_[ci]));
}

void BlockSystem::forget_changed_contacts() {
  for (const auto& [ci, terms] : factorised_terms_) terms_remembered_[ci] = 0;
  factorised_terms_.clear();
}

namespace {
bool same_term(const SpringTerm& a, const SpringTerm& b) {
  return a.block_a == b.block_a && a.block_b == b.block_b && a.stiffness == b.stiffness && a.row_a == b.row_a &&
         a.row_b == b.row_b;
}
}  // namespace

bool BlockSystem::modify_factor(StepStatistics& stats) {
  if (!settings_.low_rank_updates) return false;
  const bool same_factor = factor_of_this_step_ && held_blocks_ == factorised_held_blocks_;
  std::vector<SpringTerm> changes;
  if (same_factor)
    for (const auto& [ci, before] : factorised_terms_) {
      const ContactTerms now = contact_terms(contacts_[ci]);
      for (int k = 0; k < 4; ++k) {
        if (before.present[k] && now.present[k] && same_term(before.term[k], now.term[k])) continue;
        if (before.present[k]) {
          changes.push_back(before.term[k]);
          changes.back().stiffness = -changes.back().stiffness;
        }
        if (now.present[k]) changes.push_back(now.term[k]);
      }
    }
  forget_changed_contacts();
  const int rank = static_cast<int>(changes.size());
  if (!same_factor || rank > kMaxLowRankPerAssembly || solver_.modified_rank() + rank > kMaxLowRank) return false;
  if (changes.empty()) return true;  // the changes of this round cancelled out
  if (!solver_.modify(changes)) return false;
  // A downdate of a stiff spring can lose digits in the capacitance matrix: check a
  // solve against K itself.
  Eigen::VectorXd x_check(6 * n_blocks());
  for (int i = 0; i < x_check.size(); ++i) x_check[i] = 1.0 + 0.1 * (i % 7);
  const Eigen::VectorXd b = stiffness_.multiply(x_check);
  const double residual = (stiffness_.multiply(solver_.woodbury_check_solve(x_check)) - b).norm() / b.norm();
  if (!(residual <= kLowRankResidual)) {
    ++stats.low_rank_rejections;
    return false;
  }
  ++stats.low_rank_updates;
  stats.low_rank_terms += rank;
  return true;
}

}  // namespace hfdda::dda
