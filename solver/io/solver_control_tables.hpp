#pragma once
// The key tables of the case file's solver-control sections (contact, numerics,
// fracture, time): how the equations are solved and for how long, as opposed to what is
// modelled (case_tables.cpp).

#include "io/case_config.hpp"
#include "io/case_schema.hpp"

namespace hfdda::io {

const schema::Table<ContactConfig>& contact_table();
const schema::Table<NumericsConfig>& numerics_table();
const schema::Table<FractureCriterionConfig>& fracture_criterion_table();
const schema::Table<TimeConfig>& time_table();

}  // namespace hfdda::io
