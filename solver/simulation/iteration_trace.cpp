#include "simulation/iteration_trace.hpp"

#include <cerrno>
#include <cstring>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

#include "io/output.hpp"

namespace hfdda::simulation {

namespace {

constexpr const char* kHeader =
    "step,step_start_s,attempt_dt_s,row,iteration,contact_changes,coupled_changes,bonds_broken,cycle_holds,"
    "mechanism_blocks,overlap_fraction,overlap_joint,block_strain,strain_block,text\n";

/// A CSV field that may hold commas, quotes or line breaks.
std::string quoted(const std::string& text) {
  std::string q = "\"";
  for (const char c : text) {
    if (c == '"') q += "\"\"";
    else if (c == '\n' || c == '\r') q += ' ';
    else q += c;
  }
  return q + '"';
}

}  // namespace

IterationTrace::IterationTrace(const std::string& path, int restarted_after) : path_(path) {
  std::string kept = kHeader;
  if (restarted_after >= 0) {
    std::ifstream previous(path);
    std::string line;
    std::getline(previous, line);  // the header
    while (std::getline(previous, line))
      if (std::atoi(line.c_str()) <= restarted_after) kept += line + '\n';
  }
  io::write_file_atomically(path, kept);
  errno = 0;
  out_.open(path, std::ios::out | std::ios::app);
  if (!out_) throw std::runtime_error("cannot open '" + path + "': " + std::strerror(errno != 0 ? errno : EIO));
}

void IterationTrace::iteration(const coupling::IterationRecord& r) {
  std::ostringstream line;
  line.precision(10);
  line << step_ << ',' << start_s_ << ',' << r.attempt_dt_s << ",iteration," << r.iteration << ','
       << r.contact_changes << ',' << r.coupled_changes << ',' << r.bonds_broken << ',' << r.cycle_holds << ','
       << r.mechanism_blocks << ',' << r.overlap_fraction << ',' << r.overlap_joint << ',' << r.block_strain << ','
       << r.strain_block << ',' << quoted(r.first_change) << '\n';
  write(line.str());
}

void IterationTrace::attempt_ended(double dt_s, int iterations, const std::string& refusal) {
  std::ostringstream line;
  line.precision(10);
  line << step_ << ',' << start_s_ << ',' << dt_s << ",attempt," << iterations << ",,,,,,,,,,"
       << quoted(refusal.empty() ? "committed" : refusal) << '\n';
  write(line.str());
}

void IterationTrace::write(const std::string& line) {
  // Whole lines, flushed: a run that is killed keeps every finished row.
  out_.write(line.data(), static_cast<std::streamsize>(line.size()));
  out_.flush();
  if (!out_) throw std::runtime_error("writing '" + path_ + "' failed: " + std::strerror(errno != 0 ? errno : EIO));
}

}  // namespace hfdda::simulation
