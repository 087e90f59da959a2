#pragma once
// `breakable_patterns`: which joints of a structured mesh may break, as families of grid
// lines and cell diagonals over a rectangle (BreakablePatternConfig). Here are the key
// of the case file, its checks across keys, and the expansion of the patterns into the
// line features (FractureConfig) that the model applies to its joints.

#include "io/case_checks.hpp"
#include "io/case_config.hpp"
#include "io/case_schema.hpp"

namespace hfdda::io {

/// The top-level `breakable_patterns` key (a list of maps) and its item table.
schema::Field<CaseConfig> breakable_patterns_key();

/// Cross check: patterns need a structured mesh (on a Delaunay mesh line features are
/// mesh constraints, not a selection of joints), and diagonals a mesh whose cells have
/// both diagonals (split: four).
void check_pattern_mesh(const CaseConfig& config, const MergedChecker& checker);

/// Cross check: each pattern's region lies in domain.outer and holds at least one line,
/// and not so many that the case could not be built.
void check_pattern_regions(const CaseConfig& config, const MergedChecker& checker);

/// Appends the lines of every pattern, in order, to config.fractures. The parts of a line
/// that lie on a written fracture are left out, so those joints keep the fracture's
/// values; a later pattern overrides an earlier one where they share joints.
void append_breakable_pattern_lines(CaseConfig& config);

}  // namespace hfdda::io
