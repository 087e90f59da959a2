#include "simulation/checkpoint.hpp"

#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include "core/binary_io.hpp"
#include "io/output.hpp"

namespace hfdda::simulation {

namespace {

constexpr char kMagic[] = "HFDDA-CK";
constexpr char kEnd[] = "HFDDA-END";

void fnv1a(std::uint64_t& h, const void* data, std::size_t n) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < n; ++i) {
    h ^= p[i];
    h *= 1099511628211ull;
  }
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The target of a block-style `extends:` line, resolved like the case loader does
/// (relative to the directory of the file that names it); empty if there is none.
std::string extends_target(const std::string& text, const std::string& file) {
  static const std::regex line(R"(^extends:[ \t]*["']?([^"'#\r\n]*?)["']?[ \t]*(#.*)?$)", std::regex::multiline);
  std::smatch m;
  if (!std::regex_search(text, m, line) || m[1].str().empty()) return {};
  const std::filesystem::path target(m[1].str());
  return target.is_absolute() ? target.string() : (std::filesystem::path(file).parent_path() / target).string();
}

void put_pvd(BinaryWriter& out, const std::vector<std::pair<double, std::string>>& entries) {
  out.put<std::uint64_t>(entries.size());
  for (const auto& [t, file] : entries) {
    out.put(t);
    out.put_string(file);
  }
}

std::vector<std::pair<double, std::string>> get_pvd(BinaryReader& in) {
  std::vector<std::pair<double, std::string>> entries(in.get<std::uint64_t>());
  for (auto& [t, file] : entries) {
    in.get(t);
    file = in.get_string();
  }
  return entries;
}

}  // namespace

std::string checkpoint_path(const std::string& run_dir) { return run_dir + "/checkpoint.bin"; }

std::uint64_t case_fingerprint(const Model& model) {
  std::uint64_t h = 14695981039346656037ull;
  std::string file = model.config.file;
  for (int depth = 0; depth < 32 && !file.empty(); ++depth) {  // 32: far beyond any real chain (the loader refuses cycles)
    const std::string text = read_text(file);
    fnv1a(h, text.data(), text.size());
    file = extends_target(text, file);
  }
  for (const io::FractureMapConfig& map : model.config.fracture_maps) {  // their CSV files too
    const std::string text = read_text(map.path);
    fnv1a(h, text.data(), text.size());
  }
  // A generated network: the joints it took (a restart with another network is refused).
  if (!model.network.fractures.empty())
    fnv1a(h, model.fracture_of_joint.data(), model.fracture_of_joint.size() * sizeof(int));
  const dda::BlockSystem& system = *model.system;
  const std::int64_t sizes[] = {system.n_blocks(), static_cast<std::int64_t>(system.contacts().size()),
                                static_cast<std::int64_t>(system.mesh().points.size())};
  fnv1a(h, sizes, sizeof sizes);
  for (int b = 0; b < system.n_blocks(); ++b)
    for (int k = 0; k < system.n_corners(b); ++k) {
      const Vec2 p = system.initial_corner(b, k);
      fnv1a(h, p.data(), 2 * sizeof(double));
    }
  return h;
}

void write_checkpoint(const std::string& path, const Model& model, const RunProgress& progress) {
  static_assert(std::is_trivially_copyable_v<StepStatistics>);
  BinaryWriter out;
  out.put_string(kMagic);
  out.put(kCheckpointVersion);
  out.put(case_fingerprint(model));
  out.put(progress.step);
  out.put(progress.time_s);
  out.put(progress.wall_s);
  out.put(progress.totals);
  const RunRecord& record = progress.record;
  out.put<std::uint64_t>(record.columns().size());
  for (const std::string& c : record.columns()) out.put_string(c);
  out.put<std::uint64_t>(record.rows());
  for (std::size_t r = 0; r < record.rows(); ++r) out.put_vector(record.row(r));
  put_pvd(out, progress.blocks_pvd);
  put_pvd(out, progress.joints_pvd);
  model.system->save_state(out);
  out.put<bool>(model.flow != nullptr);
  if (model.flow) model.flow->save_state(out);
  out.put<bool>(model.ramp != nullptr);
  if (model.ramp) model.ramp->save_state(out);
  out.put_string(kEnd);
  io::write_file_atomically(path, out.bytes());
}

RunProgress read_checkpoint(const std::string& path, Model& model) {
  const std::string bytes = read_text(path);
  if (bytes.empty()) throw std::runtime_error("no checkpoint at '" + path + "'");
  const std::string where = "checkpoint '" + path + "': ";
  RunProgress progress;
  try {
    BinaryReader in(bytes);
    if (in.get_string() != kMagic) throw std::runtime_error("not a checkpoint of hfdda");
    const auto version = in.get<std::uint32_t>();
    if (version != kCheckpointVersion)
      throw std::runtime_error("format version " + std::to_string(version) + ", this build reads version " +
                               std::to_string(kCheckpointVersion));
    if (in.get<std::uint64_t>() != case_fingerprint(model))
      throw std::runtime_error("written for a different case (the case file, a file it extends or the mesh changed)");
    in.get(progress.step);
    in.get(progress.time_s);
    in.get(progress.wall_s);
    in.get(progress.totals);
    std::vector<std::string> columns(in.get<std::uint64_t>());
    for (std::string& c : columns) c = in.get_string();
    progress.record = RunRecord(columns);
    const auto rows = in.get<std::uint64_t>();
    for (std::uint64_t r = 0; r < rows; ++r) {
      std::vector<double> row;
      in.get_vector(row);
      progress.record.append(std::move(row));
    }
    progress.blocks_pvd = get_pvd(in);
    progress.joints_pvd = get_pvd(in);
    model.system->restore_state(in);
    if (in.get<bool>() != (model.flow != nullptr)) throw std::runtime_error("flow network present in one only");
    if (model.flow) model.flow->restore_state(in);
    if (in.get<bool>() != (model.ramp != nullptr)) throw std::runtime_error("load ramp present in one only");
    if (model.ramp) model.ramp->restore_state(in);
    if (in.get_string() != kEnd || in.remaining() != 0) throw std::runtime_error("unexpected data at the end");
  } catch (const std::exception& e) {
    throw std::runtime_error(where + e.what());
  }
  return progress;
}

}  // namespace hfdda::simulation
