#include "variant_pool.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>

#include "core/environment.hpp"

namespace hfdda::verification {

int variant_jobs_from_environment() { return core::whole_number_from_environment("HFDDA_VERIFY_JOBS", 1, 64); }

std::vector<VariantOutcome> run_variants_in_pool(std::size_t count, int jobs,
                                                 const std::function<VariantOutcome(std::size_t)>& run,
                                                 const std::function<void(std::size_t, const VariantOutcome&)>& report) {
  std::vector<std::optional<VariantOutcome>> outcomes(count);
  std::atomic<std::size_t> next{0};
  std::mutex reporting;
  std::exception_ptr failure;
  auto work = [&] {
    for (std::size_t i = next++; i < count; i = next++) try {
      VariantOutcome v = run(i);
      {
        const std::lock_guard<std::mutex> lock(reporting);
        report(i, v);
      }
      outcomes[i] = std::move(v);
    } catch (...) {
      // A metrics function that throws: the study stops with its error (as with one job).
      const std::lock_guard<std::mutex> lock(reporting);
      if (!failure) failure = std::current_exception();
      next = count;
    }
  };
  std::vector<std::thread> helpers;
  for (int j = 1; j < std::min<int>(jobs, static_cast<int>(count)); ++j) helpers.emplace_back(work);
  work();
  for (std::thread& t : helpers) t.join();
  if (failure) std::rethrow_exception(failure);
  std::vector<VariantOutcome> ordered;
  ordered.reserve(count);
  for (auto& v : outcomes) ordered.push_back(std::move(*v));
  return ordered;
}

}  // namespace hfdda::verification
