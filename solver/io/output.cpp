#include "io/output.hpp"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <span>
#include <stdexcept>
#include <string_view>

namespace hfdda::io {
namespace fs = std::filesystem;

namespace {

// ---------------------------------------------------------------------------
// Number formatting. std::to_chars is locale-independent (a German locale would
// otherwise turn "0.5" into "0,5" and break every reader) and about ten times faster
// than iostreams, which matters for frames with 10^5 points. Without a precision
// argument it prints the shortest text that parses back to the same double, so it
// is exact like %.17g while giving "0.1" rather than "0.10000000000000001".

void append_number(std::string& out, double value) {
  std::array<char, 32> buf;  // the longest shortest-form double has 24 characters
  const auto result = std::to_chars(buf.data(), buf.data() + buf.size(), value);
  out.append(buf.data(), result.ptr);
}

void append_integer(std::string& out, std::int64_t value) {
  std::array<char, 24> buf;
  const auto result = std::to_chars(buf.data(), buf.data() + buf.size(), value);
  out.append(buf.data(), result.ptr);
}

std::string system_error_text(const std::string& what, const std::string& path, int err) {
  return what + " '" + path + "': " + std::strerror(err);
}

// Attribute values (file names in the .pvd) must not break the XML.
std::string xml_escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

// ---------------------------------------------------------------------------
// Temporary-file handling for write_file_atomically.

void create_parent_directories(const fs::path& target) {
  const fs::path parent = target.parent_path();
  if (parent.empty()) return;
  std::error_code ec;
  fs::create_directories(parent, ec);
  if (ec) {
    throw std::runtime_error("cannot create directory '" + parent.string() + "' for '" +
                             target.string() + "': " + ec.message());
  }
}

// Writes the whole text with C stdio so that errno names the failure (disk full,
// permission) and fclose's deferred write errors are not lost.
void write_whole_file(const std::string& path, const std::string& text) {
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (file == nullptr) throw std::runtime_error(system_error_text("cannot open", path, errno));
  const std::size_t written = std::fwrite(text.data(), 1, text.size(), file);
  const int write_errno = errno;
  const bool closed = std::fclose(file) == 0;
  if (written != text.size()) {
    throw std::runtime_error(system_error_text("cannot write", path, write_errno));
  }
  if (!closed) throw std::runtime_error(system_error_text("cannot write", path, errno));
}

// ---------------------------------------------------------------------------
// VTK XML pieces, ASCII format: diff-able and readable by ParaView and meshio.

constexpr std::uint8_t kVtkLine = 3;
constexpr std::uint8_t kVtkTriangle = 5;
constexpr std::uint8_t kVtkPolygon = 7;
constexpr std::uint8_t kVtkQuad = 9;

void begin_vtu(std::string& out, std::size_t n_points, std::size_t n_cells) {
  out += "<?xml version=\"1.0\"?>\n";
  out += "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n";
  out += "  <UnstructuredGrid>\n";
  out += "    <Piece NumberOfPoints=\"";
  append_integer(out, static_cast<std::int64_t>(n_points));
  out += "\" NumberOfCells=\"";
  append_integer(out, static_cast<std::int64_t>(n_cells));
  out += "\">\n";
}

void end_vtu(std::string& out) {
  out += "    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
}

// `component_names` (e.g. {"sxx","syy","sxy"}) label the components in ParaView.
void begin_array(std::string& out, std::string_view type, std::string_view name,
                 int components = 1, std::span<const std::string_view> component_names = {}) {
  out += "        <DataArray type=\"";
  out += type;
  out += "\" Name=\"";
  out += name;
  out += "\" NumberOfComponents=\"";
  append_integer(out, components);
  out += '"';
  for (std::size_t i = 0; i < component_names.size(); ++i) {
    out += " ComponentName";
    append_integer(out, static_cast<std::int64_t>(i));
    out += "=\"";
    out += component_names[i];
    out += '"';
  }
  out += " format=\"ascii\">\n";
}

void end_array(std::string& out) { out += "        </DataArray>\n"; }

// Plane points and vectors become 3-D tuples with z = 0, as VTK requires.
void append_xy0_array(std::string& out, std::string_view name, std::span<const Vec2> values) {
  begin_array(out, "Float64", name, 3);
  for (const Vec2& v : values) {
    append_number(out, v.x());
    out += ' ';
    append_number(out, v.y());
    out += " 0\n";
  }
  end_array(out);
}

void append_scalar_array(std::string& out, std::string_view name, std::span<const double> values) {
  begin_array(out, "Float64", name);
  for (const double v : values) {
    append_number(out, v);
    out += '\n';
  }
  end_array(out);
}

void append_int32_array(std::string& out, std::string_view name, std::span<const int> values) {
  begin_array(out, "Int32", name);
  for (const int v : values) {
    append_integer(out, v);
    out += '\n';
  }
  end_array(out);
}

// Cells whose points are consecutive: cell c uses points offsets[c] .. offsets[c+1]-1,
// which holds for both writers because no point is shared between cells.
void append_consecutive_cells(std::string& out, std::span<const int> offsets,
                              std::uint8_t (*cell_type)(int n_corners)) {
  const std::size_t n_cells = offsets.empty() ? 0 : offsets.size() - 1;
  out += "      <Cells>\n";
  begin_array(out, "Int64", "connectivity");
  for (std::size_t c = 0; c < n_cells; ++c) {
    for (int i = offsets[c]; i < offsets[c + 1]; ++i) {
      if (i > offsets[c]) out += ' ';
      append_integer(out, i);
    }
    out += '\n';
  }
  end_array(out);
  begin_array(out, "Int64", "offsets");
  for (std::size_t c = 1; c <= n_cells; ++c) {
    append_integer(out, offsets[c]);
    out += '\n';
  }
  end_array(out);
  begin_array(out, "UInt8", "types");
  for (std::size_t c = 0; c < n_cells; ++c) {
    append_integer(out, cell_type(offsets[c + 1] - offsets[c]));
    out += '\n';
  }
  end_array(out);
  out += "      </Cells>\n";
}

// Triangles and quads get their own VTK types so that filters which treat them
// specially (e.g. Tessellate, cell quality) work; other polygons are generic.
std::uint8_t polygon_cell_type(int n_corners) {
  if (n_corners == 3) return kVtkTriangle;
  if (n_corners == 4) return kVtkQuad;
  return kVtkPolygon;
}

std::uint8_t line_cell_type(int /*n_corners*/) { return kVtkLine; }

// ---------------------------------------------------------------------------
// Block frame consistency: a malformed frame would otherwise yield a file that
// ParaView rejects or, worse, silently misdraws.

void check_block_frame(const BlockFrame& f) {
  const auto fail = [](const std::string& what) {
    throw std::invalid_argument("write_blocks_vtu: " + what);
  };
  if (f.corner_offsets.empty()) {
    if (!f.corners.empty()) fail("corner_offsets is empty but corners are given");
  } else {
    if (f.corner_offsets.front() != 0) fail("corner_offsets must start at 0");
    for (std::size_t b = 0; b + 1 < f.corner_offsets.size(); ++b) {
      if (f.corner_offsets[b + 1] - f.corner_offsets[b] < 3) {
        fail("block " + std::to_string(b) + " has fewer than 3 corners");
      }
    }
    if (static_cast<std::size_t>(f.corner_offsets.back()) != f.corners.size()) {
      fail("corner_offsets.back() = " + std::to_string(f.corner_offsets.back()) +
           " differs from corners.size() = " + std::to_string(f.corners.size()));
    }
  }
  const std::size_t n_blocks = f.corner_offsets.empty() ? 0 : f.corner_offsets.size() - 1;
  if (f.corner_displacement.size() != f.corners.size()) {
    fail("corner_displacement.size() = " + std::to_string(f.corner_displacement.size()) +
         " differs from corners.size() = " + std::to_string(f.corners.size()));
  }
  if (f.stress.size() != n_blocks) {
    fail("stress.size() = " + std::to_string(f.stress.size()) + " differs from " +
         std::to_string(n_blocks) + " blocks");
  }
  if (f.material.size() != n_blocks) {
    fail("material.size() = " + std::to_string(f.material.size()) + " differs from " +
         std::to_string(n_blocks) + " blocks");
  }
}

// ---------------------------------------------------------------------------
// Joint helpers.

// Ordered from most to least open, so the more open end of a joint is the minimum.
int joint_state_code(const std::string& state, int joint_id) {
  if (state == "open") return 0;
  if (state == "sliding") return 1;
  if (state == "locked") return 2;
  throw std::invalid_argument("joint " + std::to_string(joint_id) + ": unknown state '" + state +
                              "' (expected open, sliding or locked)");
}

void append_csv_row(std::string& out, const JointRow& j) {
  const std::array<double, 11> numbers{j.p.x(), j.p.y(), j.q.x(), j.q.y(), j.length_m,
                                       j.aperture_p_m, j.aperture_q_m, j.normal_stress_p_Pa,
                                       j.normal_stress_q_Pa, j.shear_stress_p_Pa,
                                       j.shear_stress_q_Pa};
  append_integer(out, j.id);
  for (const double v : numbers) {
    out += ',';
    append_number(out, v);
  }
  out += ',';
  out += j.state_p;
  out += ',';
  out += j.state_q;
  out += j.broken ? ",1" : ",0";
  out += j.natural ? ",1" : ",0";
  out += j.fluid ? ",1," : ",0,";
  append_number(out, j.pressure_p_Pa);
  out += ',';
  append_number(out, j.pressure_q_Pa);
  out += '\n';
}

}  // namespace

// ---------------------------------------------------------------------------

void write_file_atomically(const std::string& path, const std::string& text) {
  create_parent_directories(path);
  const std::string temporary = path + ".tmp." + std::to_string(::getpid());
  try {
    write_whole_file(temporary, text);
    std::error_code ec;
    fs::rename(temporary, path, ec);  // atomic on POSIX: readers see old or new, never half
    if (ec) {
      throw std::runtime_error("cannot rename '" + temporary + "' to '" + path + "': " +
                               ec.message());
    }
  } catch (...) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw;
  }
}

void write_joints_csv(const std::string& path, const std::vector<JointRow>& joints) {
  std::string out =
      "id,px,py,qx,qy,length,aperture_p,aperture_q,normal_stress_p,normal_stress_q,"
      "shear_stress_p,shear_stress_q,state_p,state_q,broken,natural,fluid,pressure_p,pressure_q\n";
  out.reserve(out.size() + joints.size() * 320);
  for (const JointRow& j : joints) append_csv_row(out, j);
  write_file_atomically(path, out);
}

void write_blocks_vtu(const std::string& path, const BlockFrame& frame) {
  check_block_frame(frame);
  const std::size_t n_blocks = frame.material.size();
  static constexpr std::array<std::string_view, 3> kStressComponents{"sxx", "syy", "sxy"};

  std::string out;
  out.reserve(1024 + frame.corners.size() * 110 + n_blocks * 90);
  begin_vtu(out, frame.corners.size(), n_blocks);

  out += "      <PointData Vectors=\"displacement\">\n";
  append_xy0_array(out, "displacement", frame.corner_displacement);
  out += "      </PointData>\n";

  out += "      <CellData Scalars=\"material\">\n";
  begin_array(out, "Float64", "stress", 3, kStressComponents);
  for (const Eigen::Vector3d& s : frame.stress) {
    append_number(out, s.x());
    out += ' ';
    append_number(out, s.y());
    out += ' ';
    append_number(out, s.z());
    out += '\n';
  }
  end_array(out);
  append_int32_array(out, "material", frame.material);
  out += "      </CellData>\n";

  out += "      <Points>\n";
  append_xy0_array(out, "Points", frame.corners);
  out += "      </Points>\n";

  append_consecutive_cells(out, frame.corner_offsets, polygon_cell_type);
  end_vtu(out);
  write_file_atomically(path, out);
}

void write_joints_vtu(const std::string& path, const std::vector<JointRow>& joints) {
  const std::size_t n = joints.size();
  std::vector<Vec2> points;
  std::vector<int> offsets{0};
  std::vector<double> aperture, normal_stress, shear_stress, pressure;
  std::vector<int> state, broken, natural, fluid, id;
  points.reserve(2 * n);
  offsets.reserve(n + 1);
  for (const JointRow& j : joints) {
    points.push_back(j.p);
    points.push_back(j.q);
    offsets.push_back(static_cast<int>(points.size()));
    aperture.push_back(0.5 * (j.aperture_p_m + j.aperture_q_m));
    normal_stress.push_back(0.5 * (j.normal_stress_p_Pa + j.normal_stress_q_Pa));
    shear_stress.push_back(0.5 * (j.shear_stress_p_Pa + j.shear_stress_q_Pa));
    pressure.push_back(0.5 * (j.pressure_p_Pa + j.pressure_q_Pa));
    // A joint open at either end conducts fluid, so it is drawn as the more open state.
    state.push_back(std::min(joint_state_code(j.state_p, j.id), joint_state_code(j.state_q, j.id)));
    broken.push_back(j.broken ? 1 : 0);
    natural.push_back(j.natural ? 1 : 0);
    fluid.push_back(j.fluid ? 1 : 0);
    id.push_back(j.id);
  }

  std::string out;
  out.reserve(1024 + n * 400);
  begin_vtu(out, points.size(), n);
  out += "      <CellData Scalars=\"state\">\n";
  append_scalar_array(out, "aperture", aperture);
  append_scalar_array(out, "normal_stress", normal_stress);
  append_scalar_array(out, "shear_stress", shear_stress);
  append_scalar_array(out, "fluid_pressure", pressure);
  append_int32_array(out, "state", state);
  append_int32_array(out, "broken", broken);
  append_int32_array(out, "natural", natural);
  append_int32_array(out, "fluid", fluid);
  append_int32_array(out, "joint_id", id);
  out += "      </CellData>\n";
  out += "      <Points>\n";
  append_xy0_array(out, "Points", points);
  out += "      </Points>\n";
  append_consecutive_cells(out, offsets, line_cell_type);
  end_vtu(out);
  write_file_atomically(path, out);
}

void write_lines_vtu(const std::string& path, const std::vector<std::pair<Vec2, Vec2>>& lines,
                     const std::vector<LineCellData>& cell_data) {
  for (const LineCellData& data : cell_data)
    if (data.values.size() != lines.size())
      throw std::invalid_argument("write_lines_vtu: array '" + data.name + "' has " +
                                  std::to_string(data.values.size()) + " values for " +
                                  std::to_string(lines.size()) + " lines");
  std::vector<Vec2> points;
  std::vector<int> offsets{0};
  points.reserve(2 * lines.size());
  offsets.reserve(lines.size() + 1);
  for (const auto& [p, q] : lines) {
    points.push_back(p);
    points.push_back(q);
    offsets.push_back(static_cast<int>(points.size()));
  }
  std::string out;
  out.reserve(1024 + lines.size() * (120 + 12 * cell_data.size()));
  begin_vtu(out, points.size(), lines.size());
  out += "      <CellData>\n";
  for (const LineCellData& data : cell_data) append_int32_array(out, data.name, data.values);
  out += "      </CellData>\n";
  out += "      <Points>\n";
  append_xy0_array(out, "Points", points);
  out += "      </Points>\n";
  append_consecutive_cells(out, offsets, line_cell_type);
  end_vtu(out);
  write_file_atomically(path, out);
}

// ---------------------------------------------------------------------------

void PvdSeries::add(double time_s, const std::string& relative_file) {
  entries_.emplace_back(time_s, relative_file);
  write();
}

void PvdSeries::restore(Entries entries) {
  entries_ = std::move(entries);
  write();
}

void PvdSeries::write() const {
  std::string out;
  out += "<?xml version=\"1.0\"?>\n";
  out += "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n";
  out += "  <Collection>\n";
  for (const auto& [time, file] : entries_) {
    out += "    <DataSet timestep=\"";
    append_number(out, time);
    out += "\" part=\"0\" file=\"";
    out += xml_escape(file);
    out += "\"/>\n";
  }
  out += "  </Collection>\n</VTKFile>\n";
  write_file_atomically(path_, out);
}

// ---------------------------------------------------------------------------

namespace {

std::string csv_line(const std::vector<double>& values) {
  std::string row;
  row.reserve(values.size() * 25);
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i > 0) row += ',';
    append_number(row, values[i]);
  }
  row += '\n';
  return row;
}

}  // namespace

HistoryCsv::HistoryCsv(const std::string& path, std::vector<std::string> columns,
                       const std::vector<std::vector<double>>& rows)
    : columns_(std::move(columns)) {
  if (columns_.empty()) throw std::invalid_argument("HistoryCsv '" + path + "': no columns");
  for (const std::string& c : columns_) {
    // A separator or line break inside a name would shift every later column.
    if (c.empty() || c.find_first_of(",\n\r\"") != std::string::npos) {
      throw std::invalid_argument("HistoryCsv '" + path + "': invalid column name '" + c + "'");
    }
  }
  std::string text;
  for (std::size_t i = 0; i < columns_.size(); ++i) {
    if (i > 0) text += ',';
    text += columns_[i];
  }
  text += '\n';
  for (const std::vector<double>& row : rows) {
    if (row.size() != columns_.size()) throw std::invalid_argument("HistoryCsv '" + path + "': row of the wrong size");
    text += csv_line(row);
  }
  write_file_atomically(path, text);
  errno = 0;
  out_.open(path, std::ios::out | std::ios::app);
  if (!out_) {
    throw std::runtime_error(system_error_text("cannot open", path, errno != 0 ? errno : EIO));
  }
}

void HistoryCsv::append(const std::vector<double>& values) {
  if (values.size() != columns_.size()) {
    throw std::invalid_argument("HistoryCsv::append: " + std::to_string(values.size()) +
                                " values for " + std::to_string(columns_.size()) + " columns");
  }
  const std::string row = csv_line(values);
  // One write of the whole line, flushed: a run that crashes or is killed keeps every
  // finished step and no partial line (the stream's buffer is empty before each row and
  // larger than a row, so the flush is a single write call).
  out_.write(row.data(), static_cast<std::streamsize>(row.size()));
  out_.flush();
  if (!out_) {
    throw std::runtime_error(std::string("HistoryCsv::append: write failed: ") +
                             std::strerror(errno));
  }
}

}  // namespace hfdda::io
