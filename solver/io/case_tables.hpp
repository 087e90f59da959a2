#pragma once
// The key table of a whole case file (the top level, with every section below it).

#include "io/case_config.hpp"
#include "io/case_schema.hpp"

namespace hfdda::io {

/// Top-level keys of a case file; parse_map() of it reads a whole file.
const schema::Table<CaseConfig>& case_table();

}  // namespace hfdda::io
