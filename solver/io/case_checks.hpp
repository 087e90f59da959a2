#pragma once
// Checks across keys, made once the whole extends chain is merged (a fracture inside
// the domain, end_time >= dt, ...). Each names the file and line where the offending key
// was last set.

#include <string>
#include <utility>
#include <vector>

#include "io/case_config.hpp"
#include "io/case_schema.hpp"

namespace hfdda::io {

/// Names the file and line of a key of the merged chain; a key never written (a
/// default) is reported at its closest written parent, else at the top file, line 0.
class MergedChecker {
 public:
  MergedChecker(const schema::Provenance& where, std::string top_file)
      : where_(&where), top_file_(std::move(top_file)) {}

  bool present(const std::string& key) const { return where_->contains(key); }

  [[noreturn]] void fail(const std::string& key, const std::string& rule) const;

 private:
  const schema::Provenance* where_;  // not owned
  std::string top_file_;
};

/// "[xmin, xmax] x [ymin, ymax]", as rectangles read in error messages.
std::string domain_text(const Rect& r);

struct CrossCheck {
  std::string rule;  ///< as written in docs/case_file.md
  void (*check)(const CaseConfig&, const MergedChecker&);
};

/// Shortest Delaunay constraint piece (`fractures[].segment_length`), as a fraction of
/// the mesh size sqrt(max_area) it meets.
inline constexpr double kMinSegmentFraction = 0.01;

/// Refuses a non-zero stress (sxx, syy, sxy of `section`) that no side in `sides`
/// would carry; `what` names it in the message ("the far-field stress").
void check_stress_sides(const MergedChecker& m, const std::string& section, double sxx, double syy, double sxy,
                        const std::vector<std::string>& sides, const std::string& what);

/// Every check across keys, in the order they run and are documented.
const std::vector<CrossCheck>& cross_checks();

}  // namespace hfdda::io
