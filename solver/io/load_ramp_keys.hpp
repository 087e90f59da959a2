#pragma once
// `load_ramp`: the quasi-static loading of seed 4.2-4.4 (LoadRampConfig). The key of the
// case file with its table, and its checks across keys.

#include "io/case_checks.hpp"
#include "io/case_config.hpp"
#include "io/case_schema.hpp"

namespace hfdda::io {

/// The top-level `load_ramp` key (an optional map) and its table.
schema::Field<CaseConfig> load_ramp_key();

/// Cross check: levels given one way (uniform ramp or history), a non-zero stress
/// pattern, a stop condition with what it needs, no flow network or prescribed
/// pressure, and no `time.end_time` (the levels set the number of steps).
void check_load_ramp(const CaseConfig& config, const MergedChecker& checker);

}  // namespace hfdda::io
