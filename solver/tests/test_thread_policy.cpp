// The thread policy: one thread runs OpenMP regions inline (no libgomp team, so no
// futex call per region, solver/dda/openmp_serial_regions.cpp); more threads go to
// libgomp unchanged; the CHOLMOD factorisation is the same either way.

#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cstdlib>
#include <stdexcept>

#include "dda/thread_policy.hpp"

namespace hfdda::dda {
namespace {

struct RegionRecord {
  int bodies = 0;
  int team_size = 0;
  int level = -1;  // nesting level of parallel regions, inactive ones included
  long iterations = 0;
};

RegionRecord run_region(int requested_threads) {
  std::atomic<int> bodies{0};
  std::atomic<long> iterations{0};
  RegionRecord r;
#pragma omp parallel num_threads(requested_threads)
  {
    ++bodies;
#pragma omp single
    {
      r.team_size = omp_get_num_threads();
      r.level = omp_get_level();
    }
#pragma omp for schedule(dynamic, 7)
    for (int i = 0; i < 1000; ++i) iterations += 1;
  }
  r.bodies = bodies;
  r.iterations = iterations;
  return r;
}

class ThreadPolicy : public ::testing::Test {
 protected:
  void TearDown() override { apply_thread_policy(1); }
};

TEST_F(ThreadPolicy, OneThreadRunsRegionsInlineAndCompletely) {
  const std::string note = apply_thread_policy(1);
  EXPECT_NE(note.find("inline"), std::string::npos) << note;
  const RegionRecord r = run_region(4);  // CHOLMOD asks for 4 whatever the setting
  EXPECT_EQ(r.bodies, 1);
  EXPECT_EQ(r.team_size, 1);
  EXPECT_EQ(r.level, 0);  // no team was formed: libgomp's own team of one has level 1
  EXPECT_EQ(r.iterations, 1000);
}

TEST_F(ThreadPolicy, TwoThreadsStillFormATeam) {
  apply_thread_policy(2);
  const RegionRecord r = run_region(2);
  EXPECT_EQ(r.bodies, 2);
  EXPECT_EQ(r.team_size, 2);
  EXPECT_EQ(r.level, 1);
  EXPECT_EQ(r.iterations, 1000);
}

TEST_F(ThreadPolicy, NoteNamesTheBlasKernelsOfTheProcessor) {
  // Long runs differ in the last bits between OpenBLAS's kernels (design notes section 32).
  const std::string note = apply_thread_policy(1);
  if (note.find("no OpenBLAS") != std::string::npos) GTEST_SKIP() << "not linked with OpenBLAS: " << note;
  EXPECT_NE(note.find("OpenBLAS 1 with "), std::string::npos) << note;
  EXPECT_NE(note.find(" kernels"), std::string::npos) << note;
}

TEST_F(ThreadPolicy, KernelsAreThoseOpenblasCoretypeNames) {
  // The scripts pin the kernels with OPENBLAS_CORETYPE (scripts/blas_kernels.sh): the
  // name OpenBLAS reports must be the one asked for, else the pin did not take.
  const char* asked = std::getenv("OPENBLAS_CORETYPE");
  if (blas_kernels().empty()) GTEST_SKIP() << "the BLAS does not name its kernels";
  if (asked == nullptr || *asked == '\0') GTEST_SKIP() << "OPENBLAS_CORETYPE not set; kernels " << blas_kernels();
  std::string a(asked), b = blas_kernels();
  for (std::string* t : {&a, &b}) std::transform(t->begin(), t->end(), t->begin(), [](unsigned char c) { return std::tolower(c); });
  EXPECT_EQ(a, b) << "asked for " << asked << ", OpenBLAS runs " << blas_kernels();
  EXPECT_NE(apply_thread_policy(1).find("with " + blas_kernels() + " kernels"), std::string::npos);
}

TEST_F(ThreadPolicy, RefusesZeroThreads) { EXPECT_THROW(apply_thread_policy(0), std::invalid_argument); }

}  // namespace
}  // namespace hfdda::dda
