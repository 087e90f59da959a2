#pragma once
// Running an ensemble: its directory, the realisations one process takes from a work
// queue, their records, and the likelihood maps taken over every record found.
//
// Directory layout (docs/ensembles.md):
//   DIR/ensemble.json              what the ensemble is (case, seeds, maps, mesh, shard)
//   DIR/realisations/r<i>.json     one per finished realisation, written atomically
//   DIR/likelihood_*.csv|vtu|pvd   the maps (likelihood_maps.hpp)
//   DIR/ensemble_summary.json      counts, failures with reasons, run times
//
// The maps are a function of the set of records alone: 1, 2 or 4 processes, any shards
// merged, or a run resumed after an interruption give the same files byte for byte.

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "ensemble/realisation.hpp"
#include "io/case_config.hpp"

namespace hfdda::ensemble {

/// Which realisations a process group runs: those with index % shards == shard.
struct Shard {
  int index = 0;
  int count = 1;
  bool contains(long realisation) const { return realisation % count == index; }
};

/// What an ensemble directory holds (DIR/ensemble.json); two directories merge when
/// everything but the shard agrees.
struct EnsembleManifest {
  std::string case_file;
  std::string case_hash;       ///< of the case files read (the extends chain), 16 hex digits
  /// Of the running executable (/proc/self/exe), 16 hex digits: another build of the
  /// solver may give other realisations, so a directory is resumed only by the same build.
  std::string solver_build;
  int realisations = 0;
  int master_seed = 0;
  std::vector<std::string> resample;
  std::vector<double> map_times_s;
  MapGrid grid;
  MeshSignature mesh;
  Shard shard;
};
EnsembleManifest make_manifest(const io::CaseConfig& config, const EnsembleGeometry& geometry, Shard shard);

/// Creates DIR (and DIR/realisations) with its manifest and the joints' geometry
/// (DIR/ensemble_joints.csv), or checks that an existing DIR holds the same ensemble
/// (resume). Throws std::runtime_error naming what differs.
void prepare_directory(const std::string& dir, const EnsembleManifest& manifest, const EnsembleGeometry& geometry);

/// The realisations of `shard` without a record in DIR, in increasing order.
std::vector<long> pending_realisations(const std::string& dir, const EnsembleManifest& manifest);

/// Writes DIR/realisations/r<index>.json atomically; reads one back (throws naming the file).
void write_record(const std::string& dir, const RealisationRecord& record);
RealisationRecord read_record(const std::string& path);
/// Every record of DIR, sorted by index.
std::vector<RealisationRecord> read_records(const std::string& dir);

/// How one finished realisation went, for the work queue's progress.
struct Outcome {
  bool failed = false;
  double wall_s = 0.0;
};

/// Hands out realisation indices. A serial run takes them in order; the MPI farm
/// (cli/ensemble_mpi.cpp) hands them out one at a time from rank 0 as ranks come free.
class WorkQueue {
 public:
  virtual ~WorkQueue() = default;
  /// The next realisation for this process, or none when all are handed out;
  /// `finished` tells how the previous one of this process went.
  virtual std::optional<long> next(const std::optional<Outcome>& finished) = 0;
  /// Called between steps while a realisation runs (rank 0 answers the others there when
  /// MPI gives it no service thread).
  virtual void serve() {}
  /// After the last next(): rank 0 waits for every other process to finish.
  virtual void finish() {}
  /// The rank of this process (0 on one process).
  virtual int process() const { return 0; }
};

/// In order, one process.
class SerialQueue : public WorkQueue {
 public:
  SerialQueue(std::vector<long> pending, bool show_progress);
  std::optional<long> next(const std::optional<Outcome>& finished) override;

 private:
  std::vector<long> pending_;
  std::size_t cursor_ = 0;
  bool show_progress_;
  int done_ = 0, failed_ = 0;
  double wall_s_ = 0.0;
};

/// Progress text: realisations done, failed, running, and the time left from the mean
/// wall time of those done so far over `processes` processes.
std::string progress_text(int done, int failed, int running, int total, double mean_wall_s, int processes);

/// Runs the realisations the queue hands to this process, writing each record as soon as
/// it is finished. Returns false when stopped on request (the realisation in flight is
/// dropped; re-running resumes). Throws when a realisation's model cannot be built.
bool run_realisations(const io::CaseConfig& config, const EnsembleGeometry& geometry, const std::string& dir,
                      WorkQueue& queue, const std::function<bool()>& stop_requested);

/// What an ensemble's maps were taken over.
struct EnsembleSummary {
  int requested = 0;       ///< realisations of the ensemble (all shards)
  int found = 0;           ///< records read
  int completed = 0;
  int failed = 0;
  /// Completed, but some step strained a block beyond kImplausibleStepStrain (they stay
  /// in the maps; ensemble_summary.json lists them).
  int completed_with_strained_blocks = 0;
  std::vector<long> missing;  ///< indices without a record (shards not merged, or not yet run)
};

/// Reads the records of `dirs` (same ensemble, disjoint or identical records), writes the
/// likelihood maps and DIR/ensemble_summary.json into `out_dir`. Throws
/// std::runtime_error when the directories hold different ensembles.
EnsembleSummary write_ensemble_maps(const std::string& out_dir, const std::vector<std::string>& dirs);

}  // namespace hfdda::ensemble
