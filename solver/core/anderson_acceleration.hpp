#pragma once

// Anderson acceleration of a fixed-point iteration x = G(x) (D. G. Anderson, J. ACM 12,
// 1965; in the form of H. F. Walker and P. Ni, SIAM J. Numer. Anal. 49, 2011). The next
// iterate mixes the last few evaluations of G so that the residuals f = G(x) - x combine
// to the smallest norm. For a linear map it is a Krylov method (GMRES-like) on the last
// `depth` directions, so it converges where plain iteration x <- G(x) diverges because
// the map's gain exceeds one, as in a wedge of sliding contacts whose friction feeds the
// other's normal force (docs/design_notes.md section 48).

#include <deque>

#include <Eigen/Dense>

namespace hfdda {

class AndersonAcceleration {
 public:
  explicit AndersonAcceleration(int depth) : depth_(depth) {}

  /// Forget the history (a new fixed-point problem).
  void reset();

  /// x: the iterate G was evaluated at; g = G(x). Returns the next iterate: g itself
  /// until a difference is known, then g - dG gamma with gamma minimising
  /// |f - dF gamma| over the stored differences. A change of size starts afresh.
  Eigen::VectorXd next(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& g);

  /// Stored differences (0 after reset and after the first evaluation).
  int columns() const { return static_cast<int>(dg_.size()); }

 private:
  int depth_;
  std::deque<Eigen::VectorXd> dg_, df_;
  Eigen::VectorXd g_previous_, f_previous_;
  bool has_previous_ = false;
};

}  // namespace hfdda
