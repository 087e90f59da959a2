#include "core/anderson_acceleration.hpp"

namespace hfdda {

void AndersonAcceleration::reset() {
  dg_.clear();
  df_.clear();
  has_previous_ = false;
}

Eigen::VectorXd AndersonAcceleration::next(const Eigen::Ref<const Eigen::VectorXd>& x,
                                           const Eigen::Ref<const Eigen::VectorXd>& g) {
  if (has_previous_ && g.size() != g_previous_.size()) reset();
  const Eigen::VectorXd f = g - x;
  if (has_previous_) {
    dg_.push_back(g - g_previous_);
    df_.push_back(f - f_previous_);
    if (static_cast<int>(dg_.size()) > depth_) {
      dg_.pop_front();
      df_.pop_front();
    }
  }
  g_previous_ = g;
  f_previous_ = f;
  has_previous_ = true;
  if (dg_.empty()) return g;
  const int m = static_cast<int>(dg_.size());
  Eigen::MatrixXd dF(f.size(), m), dG(g.size(), m);
  for (int j = 0; j < m; ++j) {
    dF.col(j) = df_[j];
    dG.col(j) = dg_[j];
  }
  // Rank-revealing: two equal residual differences (a contact that no longer moves)
  // must not make the least-squares problem singular.
  const Eigen::VectorXd gamma = dF.completeOrthogonalDecomposition().solve(f);
  Eigen::VectorXd next = g - dG * gamma;
  if (!next.allFinite()) {
    reset();
    return g;
  }
  return next;
}

}  // namespace hfdda
