// Processes of `hfdda ensemble` (ensemble_farm.hpp).

#include "cli/ensemble_farm.hpp"

#include <time.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

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

void nap() {
  const timespec one_ms{0, 1000000};
  nanosleep(&one_ms, nullptr);
}

#ifdef HFDDA_HAVE_MPI

constexpr int kTagRequest = 1;  // worker -> rank 0: {outcome, wall in microseconds}
constexpr int kTagIndex = 2;    // rank 0 -> worker: next index, or -1
constexpr std::int64_t kNone = 0, kCompleted = 1, kFailed = 2;

/// Rank 0: hands out realisations to itself (in next()) and to the other ranks (in
/// serve(), between its own steps), and keeps the progress counts.
class Dispatcher : public ensemble::WorkQueue {
 public:
  Dispatcher(int size, std::vector<long> pending, bool show_progress)
      : size_(size), pending_(std::move(pending)), show_progress_(show_progress), terminal_(isatty(fileno(stderr))) {}

  std::optional<long> next(const std::optional<ensemble::Outcome>& finished) override {
    if (finished) count(finished->failed ? kFailed : kCompleted, finished->wall_s), --running_;
    serve();
    std::optional<long> index = take();
    if (index) ++running_;
    report(true);
    return index;
  }

  void serve() override {
    int waiting = 0;
    MPI_Status status;
    while (MPI_Iprobe(MPI_ANY_SOURCE, kTagRequest, MPI_COMM_WORLD, &waiting, &status) == MPI_SUCCESS && waiting) {
      std::int64_t request[2];
      MPI_Recv(request, 2, MPI_INT64_T, status.MPI_SOURCE, kTagRequest, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      if (request[0] != kNone) count(request[0], request[1] * 1e-6), --running_;
      const std::optional<long> index = take();
      std::int64_t reply = index ? *index : -1;
      if (index) ++running_;
      else ++retired_;
      MPI_Send(&reply, 1, MPI_INT64_T, status.MPI_SOURCE, kTagIndex, MPI_COMM_WORLD);
      report(false);
    }
  }

  void finish() override {
    while (retired_ < size_ - 1) {
      serve();
      nap();
    }
    report(true);
    if (show_progress_ && terminal_) std::fprintf(stderr, "\n");
  }

 private:
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
};

/// Ranks > 0: ask rank 0 for the next realisation, reporting how the last one went.
class Worker : public ensemble::WorkQueue {
 public:
  explicit Worker(std::function<bool()> stop_requested) : stop_requested_(std::move(stop_requested)) {}

  std::optional<long> next(const std::optional<ensemble::Outcome>& finished) override {
    std::int64_t request[2] = {kNone, 0};
    if (finished) request[0] = finished->failed ? kFailed : kCompleted, request[1] = std::llround(finished->wall_s * 1e6);
    MPI_Send(request, 2, MPI_INT64_T, 0, kTagRequest, MPI_COMM_WORLD);
    std::int64_t reply = -1;
    MPI_Request pending;
    MPI_Irecv(&reply, 1, MPI_INT64_T, 0, kTagIndex, MPI_COMM_WORLD, &pending);
    int done = 0;
    // Rank 0 answers between its own steps: wait asleep, not spinning on a shared core.
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
  std::function<bool()> stop_requested_;
};

#endif  // HFDDA_HAVE_MPI

}  // namespace

ProcessGroup start_processes(int* argc, char*** argv) {
  ProcessGroup group;
  const int size = launcher_size();
  if (size == 0) return group;
#ifdef HFDDA_HAVE_MPI
  MPI_Init(argc, argv);
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
    if (group.rank == 0) return std::make_unique<Dispatcher>(group.size, std::move(pending), show_progress);
    return std::make_unique<Worker>(std::move(stop_requested));
  }
#else
  (void)group;
#endif
  (void)stop_requested;
  return std::make_unique<ensemble::SerialQueue>(std::move(pending), show_progress);
}

}  // namespace hfdda::cli
