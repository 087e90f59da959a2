#pragma once
// The crack tips of a block system for the toughness criterion
// (fracture/toughness_criterion.hpp): where they are, from the joint states and the
// mesh's joints around each point, and their crack-closure data (fracture::CrackTip) at
// a set of contact forces and a step displacement.
//
// A crack tip is a point where a broken joint (neither contact bonded) ends and at least
// one joint with its contact there still bonded points forward, away from every broken
// joint at the point (direction . broken direction < 0). Of those, the one most nearly
// continuing a broken joint is the reference for G; the joint that fails is the
// breakable forward one nearest the kink direction of the maximum hoop stress rule. Every
// intact joint at a tip point is governed by the toughness criterion, not by its
// strength; bonds elsewhere (an uncracked body, the faces of a crack) keep the strength
// rule.

#include <vector>

#include <Eigen/Core>

#include "dda/block_system.hpp"
#include "fracture/toughness_criterion.hpp"

namespace hfdda::coupling {

/// One crack tip and the joint that fails there if its criterion is met.
struct CrackTipState {
  fracture::CrackTip tip;
  Vec2 direction{1.0, 0.0};   ///< e of the tip's frame: along the joint ahead, from the tip
  int failing_joint = -1;     ///< breakable forward joint nearest the kink (-1: none may fail)
  int failing_contact = -1;   ///< its contact at the tip point
};

class CrackTips {
 public:
  /// The joints at every point (the mesh's joint adjacency), built once.
  explicit CrackTips(const dda::BlockSystem& system);

  /// The tips of the current contact states. `tractions`: forces of every joint contact
  /// (tension positive; the trial forces of an open-close iteration, or committed ones);
  /// `d`: the step displacement those forces belong to (empty: the committed state).
  /// `governed` (per joint contact) is set for both contacts of every intact joint at a tip.
  void find(const dda::BlockSystem& system, const std::vector<dda::ContactTraction>& tractions,
            const Eigen::VectorXd& d, std::vector<CrackTipState>& tips, std::vector<char>& governed) const;

  /// The committed forces of every joint contact, in the form find() reads.
  static std::vector<dda::ContactTraction> committed_tractions(const dda::BlockSystem& system);

 private:
  /// The broken joint (both contacts unbonded) at the far end of `behind` that continues
  /// it away from `tip_point` within about 18 degrees; -1 if there is none.
  int continuing_broken_joint(const dda::BlockSystem& system, int behind, int tip_point) const;

  std::vector<int> joint_offset_;  // joints at point p: joints_[joint_offset_[p] .. joint_offset_[p + 1])
  std::vector<int> joints_;
};

}  // namespace hfdda::coupling
