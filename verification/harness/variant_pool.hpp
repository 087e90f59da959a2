#pragma once
// Runs a study's variants side by side (HFDDA_VERIFY_JOBS): a pool of threads, each
// variant on one of them under the one-thread policy. A variant's run is a process-like
// unit (its own model, files and factorisations); nothing is shared between runs but
// read-only study data.

#include <cstddef>
#include <functional>
#include <vector>

#include "harness.hpp"

namespace hfdda::verification {

/// HFDDA_VERIFY_JOBS if set (a whole number from 1 to 64), else 1. Throws
/// std::invalid_argument naming the variable for any other value.
int variant_jobs_from_environment();

/// run(i) for i = 0 .. count - 1, `jobs` at a time; report(i, outcome) as each finishes
/// (one report at a time, in the order they finish). Returns the outcomes in index
/// order. The first exception a run throws stops the pool (runs in flight finish) and
/// is rethrown.
std::vector<VariantOutcome> run_variants_in_pool(std::size_t count, int jobs,
                                                 const std::function<VariantOutcome(std::size_t)>& run,
                                                 const std::function<void(std::size_t, const VariantOutcome&)>& report);

}  // namespace hfdda::verification
