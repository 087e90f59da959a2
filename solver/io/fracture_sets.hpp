#pragma once
// `fracture_sets` and `network_seed`: stochastic natural-fracture networks grown on the
// Delaunay mesh (seed 5.3). Here are the case-file keys with their tables and checks;
// the generator itself is solver/networks/fracture_network_generator.hpp, called when
// the model is built.

#include "io/case_checks.hpp"
#include "io/case_config.hpp"
#include "io/case_schema.hpp"

namespace hfdda::io {

/// The top-level `fracture_sets` key (a list of maps) and its item tables.
schema::Field<CaseConfig> fracture_sets_key();

/// The top-level `network_seed` key.
schema::Field<CaseConfig> network_seed_key();

/// Cross check: sets need a Delaunay mesh; `network_seed` needs a set; set names are
/// distinct and differ from the names of fractures, fracture maps and breakable
/// patterns; the shortest length of a set fits in the domain.
void check_fracture_sets(const CaseConfig& config, const MergedChecker& checker);

}  // namespace hfdda::io
