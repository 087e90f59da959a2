#pragma once
// `hfdda ensemble`: Monte Carlo realisations of a case and their likelihood maps, on one
// process, on the ranks of an MPI job, or as shards merged afterwards.

namespace hfdda::cli {

/// argv[1] is "ensemble". Exit codes as the other commands: 0 done, 2 bad input or
/// unusable directory, 3 interrupted (re-running the same command resumes).
int ensemble_command(int argc, char** argv);

}  // namespace hfdda::cli
