#pragma once
// `fracture_maps`: natural fractures given as line segments in CSV files (outcrop maps,
// image logs, other DFN tools). Here are the case-file key, and the reading of the files
// into line features (FractureConfig) appended to the case's fractures, with an error
// naming the CSV file, line and column for every bad row.

#include "io/case_config.hpp"
#include "io/case_schema.hpp"

namespace hfdda::io {

/// The top-level `fracture_maps` key (a list of maps) and its item table.
schema::Field<CaseConfig> fracture_maps_key();

/// Reads every map's CSV and appends one FractureConfig per row to config.fractures
/// (named "<map>.<row>", the map's values, then the row's own columns). Throws
/// InputError naming the CSV file and line: a missing or unknown column, a bad number,
/// a zero-length segment, one outside domain.outer, a duplicate of an earlier row
/// (same ends, in either order). No limit on the number of rows.
void append_fracture_map_lines(CaseConfig& config);

}  // namespace hfdda::io
