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

void BlockSystem::remember_assembled_terms(int ci) {
  if (logged_from_version_ < 0) return;  // no assembly of this step to compare with yet
  if (terms_remembered_.size() != contacts_.all().size()) terms_remembered_.assign(contacts_.all().size(), 0);
  if (terms_remembered_[ci]) return;
  terms_remembered_[ci] = 1;
  assembled_terms_.emplace_back(ci, contact_terms(contacts_[ci]));
}

namespace {
bool same_term(const SpringTerm& a, const SpringTerm& b) {
  return a.block_a == b.block_a && a.block_b == b.block_b && a.stiffness == b.stiffness && a.row_a == b.row_a &&
         a.row_b == b.row_b;
}
}  // namespace

void BlockSystem::log_spring_changes() {
  ++stiffness_version_;
  if (logged_from_version_ < 0 || held_blocks_ != assembled_held_blocks_) {
    // The first K of the step, or the mechanism holds changed its block terms: the base
    // of the log from here on.
    spring_log_.clear();
    spring_log_version_.clear();
    logged_from_version_ = stiffness_version_;
  } else {
    for (const auto& [ci, before] : assembled_terms_) {
      const ContactTerms now = contact_terms(contacts_[ci]);
      for (int k = 0; k < 4; ++k) {
        if (before.present[k] && now.present[k] && same_term(before.term[k], now.term[k])) continue;
        if (before.present[k]) {
          spring_log_.push_back(before.term[k]);
          spring_log_.back().stiffness = -spring_log_.back().stiffness;
          spring_log_version_.push_back(stiffness_version_);
        }
        if (now.present[k]) {
          spring_log_.push_back(now.term[k]);
          spring_log_version_.push_back(stiffness_version_);
        }
      }
    }
  }
  for (const auto& entry : assembled_terms_) terms_remembered_[entry.first] = 0;
  assembled_terms_.clear();
  assembled_held_blocks_ = held_blocks_;
}

bool BlockSystem::spring_changes_since(int since, std::vector<SpringTerm>& changes) const {
  changes.clear();
  if (logged_from_version_ < 0 || since < logged_from_version_ || since > stiffness_version_) return false;
  for (std::size_t i = 0; i < spring_log_.size(); ++i)
    if (spring_log_version_[i] > since) changes.push_back(spring_log_[i]);
  return true;
}

bool BlockSystem::modify_factor(StepStatistics& stats) {
  if (!settings_.low_rank_updates) return false;
  const bool same_factor = factor_of_this_step_ && held_blocks_ == factorised_held_blocks_;
  std::vector<SpringTerm> changes;
  // The factor is of the previous assembly's K (factorised or modified since): this
  // assembly's changes are what it lacks.
  if (!same_factor || !spring_changes_since(stiffness_version_ - 1, changes)) return false;
  const int rank = static_cast<int>(changes.size());
  if (rank > kMaxLowRankPerAssembly || solver_.modified_rank() + rank > kMaxLowRank) return false;
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
