// Processes of `hfdda ensemble` (ensemble_farm.hpp).

#include "cli/ensemble_farm.hpp"

#include <time.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <stdexcept>
#include <thread>

#ifdef HFDDA_HAVE_MPI
#include <mpi.h>
#endif

namespace hfdda::cli {

namespace {

/// The size an MPI launcher gives this process in its environment (0: not launched by one).
int launcher_size() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE", "MPI_LOCALNRANKS"})
    if (const char* v = std::getenv(name)) return std::atoi(v);
  return 0;
}

void nap(long milliseconds = 1) {
  const timespec pause{milliseconds / 1000, (milliseconds % 1000) * 1000000};
  nanosleep(&pause, nullptr);
}

#ifdef HFDDA_HAVE_MPI

constexpr int kTagRequest = 1;  // worker -> rank 0: {outcome, wall in microseconds}
constexpr int kTagIndex = 2;    // rank 0 -> worker: next index, or -1
constexpr std::int64_t kNone = 0, kCompleted = 1, kFailed = 2;
/// Rank 0's service thread looks for requests this often: each look wakes a thread on a
/// core a solver computes on, so not every millisecond, while a realisation lasts
/// seconds (design notes section 20).
constexpr long kServicePollMs = 20;

/// Rank 0: hands out realisations to itself (in next()) and to the other ranks. A
/// service thread answers the other ranks within kServicePollMs, whatever rank 0's own
/// realisation is doing: answered only between rank 0's time steps, a rank that came
/// free waited for the rest of that step, which in a network realisation can take tens
/// of seconds (traced: 99 s of waiting in the Marcellus study, design notes section 20).
/// Without MPI_THREAD_SERIALIZED (an MPI built without thread support) rank 0
/// answers between its steps, as serve() is called there.
class Dispatcher : public ensemble::WorkQueue {
 public:
  Dispatcher(int size, std::vector<long> pending, bool show_progress, bool threaded)
      : size_(size), pending_(std::move(pending)), show_progress_(show_progress), terminal_(isatty(fileno(stderr))) {
    if (threaded && size_ > 1) service_ = std::thread([this] { answer_until_stopped(); });
  }
  ~Dispatcher() override { stop_service(); }

  std::optional<long> next(const std::optional<ensemble::Outcome>& finished) override {
    if (!service_.joinable()) serve();
    std::lock_guard<std::mutex> lock(mutex_);
    if (finished) count(finished->failed ? kFailed : kCompleted, finished->wall_s), --running_;
    std::optional<long> index = take();
    if (index) ++running_;
    report(true);
    return index;
  }

  void serve() override {
    if (service_.joinable()) return;
    while (answer_one()) {
    }
  }

  void finish() override {
    for (;;) {
      if (!service_.joinable()) serve();
      {
        std::lock_guard<std::mutex> lock(mutex_);
        if (retired_ >= size_ - 1) break;
      }
      nap();
    }
    stop_service();
    std::lock_guard<std::mutex> lock(mutex_);
    report(true);
    if (show_progress_ && terminal_) std::fprintf(stderr, "\n");
  }

 private:
  /// Answers one waiting request; false when none is waiting. MPI is called from one
  /// thread at a time: the service thread while it runs, the main thread otherwise.
  bool answer_one() {
    int waiting = 0;
    MPI_Status status;
    if (MPI_Iprobe(MPI_ANY_SOURCE, kTagRequest, MPI_COMM_WORLD, &waiting, &status) != MPI_SUCCESS || !waiting)
      return false;
    std::int64_t request[2];
    MPI_Recv(request, 2, MPI_INT64_T, status.MPI_SOURCE, kTagRequest, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    std::int64_t reply = -1;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (request[0] != kNone) count(request[0], request[1] * 1e-6), --running_;
      const std::optional<long> index = take();
      if (index) reply = *index, ++running_;
      else ++retired_;
      report(false);
    }
    MPI_Send(&reply, 1, MPI_INT64_T, status.MPI_SOURCE, kTagIndex, MPI_COMM_WORLD);
    return true;
  }
  void answer_until_stopped() {
    while (!stopping_.load()) {
      if (!answer_one()) nap(kServicePollMs);
    }
  }
  void stop_service() {
    if (!service_.joinable()) return;
    stopping_.store(true);
    service_.join();
  }
  std::optional<long> take() {
    if (cursor_ >= pending_.size()) return std::nullopt;
    return pending_[cursor_++];
  }
  void count(std::int64_t outcome, double wall_s) {
    ++done_;
    failed_ += outcome == kFailed;
    wall_s_ += wall_s;
  }
  void report(bool own) {
    if (!show_progress_ || (!own && done_ == shown_done_)) return;
    shown_done_ = done_;
    const std::string text = ensemble::progress_text(done_, failed_, running_, static_cast<int>(pending_.size()),
                                                     done_ > 0 ? wall_s_ / done_ : 0.0, size_);
    std::fprintf(stderr, terminal_ ? "\r%s   " : "%s\n", text.c_str());
  }

  int size_;
  std::vector<long> pending_;
  std::size_t cursor_ = 0;
  bool show_progress_, terminal_;
  int done_ = 0, failed_ = 0, running_ = 0, retired_ = 0, shown_done_ = -1;
  double wall_s_ = 0.0;
  std::mutex mutex_;  // the counts and the cursor, shared by the service thread and next()
  std::atomic<bool> stopping_{false};
  std::thread service_;
};

/// Ranks > 0: ask rank 0 for the next realisation, reporting how the last one went.
class Worker : public ensemble::WorkQueue {
 public:
  Worker(int rank, std::function<bool()> stop_requested) : rank_(rank), stop_requested_(std::move(stop_requested)) {}
  int process() const override { return rank_; }

  std::optional<long> next(const std::optional<ensemble::Outcome>& finished) override {
    std::int64_t request[2] = {kNone, 0};
    if (finished) request[0] = finished->failed ? kFailed : kCompleted, request[1] = std::llround(finished->wall_s * 1e6);
    MPI_Send(request, 2, MPI_INT64_T, 0, kTagRequest, MPI_COMM_WORLD);
    std::int64_t reply = -1;
    MPI_Request pending;
    MPI_Irecv(&reply, 1, MPI_INT64_T, 0, kTagIndex, MPI_COMM_WORLD, &pending);
    int done = 0;
    // Wait asleep, not spinning on a core another rank computes on.
    while (MPI_Test(&pending, &done, MPI_STATUS_IGNORE) == MPI_SUCCESS && !done) {
      if (stop_requested_ && stop_requested_()) {
        MPI_Cancel(&pending);
        MPI_Wait(&pending, MPI_STATUS_IGNORE);
        return std::nullopt;
      }
      nap();
    }
    if (reply < 0) return std::nullopt;
    return static_cast<long>(reply);
  }

 private:
  int rank_;
  std::function<bool()> stop_requested_;
};

#endif  // HFDDA_HAVE_MPI

}  // namespace

ProcessGroup start_processes(int* argc, char*** argv) {
  ProcessGroup group;
  const int size = launcher_size();
  if (size == 0) return group;
#ifdef HFDDA_HAVE_MPI
  int provided = MPI_THREAD_SINGLE;
  // Rank 0's dispatcher answers from a thread of its own, one MPI call at a time.
  MPI_Init_thread(argc, argv, MPI_THREAD_SERIALIZED, &provided);
  group.threaded_dispatch = provided >= MPI_THREAD_SERIALIZED;
  MPI_Comm_rank(MPI_COMM_WORLD, &group.rank);
  MPI_Comm_size(MPI_COMM_WORLD, &group.size);
  group.mpi = true;
#else
  (void)argc, (void)argv;
  if (size > 1)
    throw std::runtime_error("launched as " + std::to_string(size) +
                             " MPI processes, but this hfdda was built without MPI (install libopenmpi-dev and "
                             "rebuild; or use --shard k/n and `hfdda ensemble merge`)");
#endif
  return group;
}

void end_processes(const ProcessGroup& group) {
#ifdef HFDDA_HAVE_MPI
  if (group.mpi) MPI_Finalize();
#else
  (void)group;
#endif
}

int share_from_rank0(const ProcessGroup& group, int value) {
#ifdef HFDDA_HAVE_MPI
  if (group.mpi && group.size > 1) MPI_Bcast(&value, 1, MPI_INT, 0, MPI_COMM_WORLD);
#else
  (void)group;
#endif
  return value;
}

std::unique_ptr<ensemble::WorkQueue> make_work_queue(const ProcessGroup& group, std::vector<long> pending,
                                                     bool show_progress, std::function<bool()> stop_requested) {
#ifdef HFDDA_HAVE_MPI
  if (group.mpi && group.size > 1) {
    if (group.rank == 0) return std::make_unique<Dispatcher>(group.size, std::move(pending), show_progress, group.threaded_dispatch);
    return std::make_unique<Worker>(group.rank, std::move(stop_requested));
  }
#else
  (void)group;
#endif
  (void)stop_requested;
  return std::make_unique<ensemble::SerialQueue>(std::move(pending), show_progress);
}

}  // namespace hfdda::cli
