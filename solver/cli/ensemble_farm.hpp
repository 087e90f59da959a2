#pragma once
// The processes of `hfdda ensemble`: one process, or the ranks of an MPI job
// (`mpirun -n N hfdda ensemble ...`) among which rank 0 hands out the realisations one
// at a time as ranks come free (dynamic balancing: realisations differ widely in cost).
// MPI stays in this file pair; the solver library builds and runs without it.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "ensemble/ensemble_run.hpp"

namespace hfdda::cli {

struct ProcessGroup {
  int rank = 0;
  int size = 1;
  bool mpi = false;  ///< started with MPI_Init_thread (launched by mpirun)
  bool threaded_dispatch = false;  ///< MPI allows rank 0 to answer the others from a thread of its own
};

/// Starts MPI when this process was launched by an MPI launcher (its environment says
/// so); otherwise a group of one. Throws std::runtime_error when launched by mpirun with
/// several ranks but built without MPI.
ProcessGroup start_processes(int* argc, char*** argv);
/// MPI_Finalize when MPI was started.
void end_processes(const ProcessGroup& group);

/// Rank 0's value of `value` on every rank (MPI_Bcast; the value itself for one process).
int share_from_rank0(const ProcessGroup& group, int value);

/// The work queue of this process: the pending realisations in order for one process;
/// for MPI, rank 0 hands them out (pending is read on rank 0 only) and answers the others
/// from a service thread as soon as they ask (between the steps of its own realisations
/// when MPI offers no thread support). Waiting ranks sleep between polls rather
/// than spin, so that ranks sharing cores do not slow each other. `stop_requested` ends a
/// wait. `show_progress`: rank 0 prints done / failed / running / time left.
std::unique_ptr<ensemble::WorkQueue> make_work_queue(const ProcessGroup& group, std::vector<long> pending,
                                                     bool show_progress, std::function<bool()> stop_requested);

}  // namespace hfdda::cli
