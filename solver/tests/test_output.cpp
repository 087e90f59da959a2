#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "io/output.hpp"

namespace hfdda::io {
namespace {
namespace fs = std::filesystem;

// A fresh directory per test, removed afterwards, so tests can run in parallel (ctest -j).
class OutputTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("hfdda_output_" + std::to_string(::getpid()) + "_" + info->test_suite_name() + "_" +
            info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(dir_, ignored);
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  fs::path dir_;
};

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::string> file_names(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (e.is_regular_file()) names.push_back(e.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

// --- A deliberately tiny reader for the VTU files we write --------------------
// Not a general XML parser: it only knows DataArray elements and tag attributes,
// enough to check that counts, offsets and connectivity agree.

std::string attribute(const std::string& tag, const std::string& key) {
  const std::string pattern = " " + key + "=\"";
  const std::size_t start = tag.find(pattern);
  if (start == std::string::npos) return {};
  const std::size_t begin = start + pattern.size();
  return tag.substr(begin, tag.find('"', begin) - begin);
}

std::string opening_tag(const std::string& xml, const std::string& element) {
  const std::size_t start = xml.find("<" + element + " ");
  if (start == std::string::npos) return {};
  return xml.substr(start, xml.find('>', start) - start + 1);
}

struct DataArray {
  std::string type, name;
  int components = 1;
  std::vector<std::string> values;
  double number(std::size_t i) const { return std::stod(values.at(i)); }
  long integer(std::size_t i) const { return std::stol(values.at(i)); }
};

std::map<std::string, DataArray> data_arrays(const std::string& xml, int* count) {
  std::map<std::string, DataArray> arrays;
  *count = 0;
  for (std::size_t pos = xml.find("<DataArray "); pos != std::string::npos;
       pos = xml.find("<DataArray ", pos + 1)) {
    const std::size_t tag_end = xml.find('>', pos);
    const std::size_t close = xml.find("</DataArray>", tag_end);
    const std::string tag = xml.substr(pos, tag_end - pos + 1);
    DataArray a;
    a.type = attribute(tag, "type");
    a.name = attribute(tag, "Name");
    a.components = std::stoi(attribute(tag, "NumberOfComponents"));
    EXPECT_EQ(attribute(tag, "format"), "ascii");
    std::istringstream body(xml.substr(tag_end + 1, close - tag_end - 1));
    for (std::string v; body >> v;) a.values.push_back(v);
    arrays[a.name] = a;
    ++*count;
  }
  return arrays;
}

struct Vtu {
  long n_points = -1, n_cells = -1;
  int n_arrays = 0;
  std::map<std::string, DataArray> arrays;
  const DataArray& operator[](const std::string& name) const { return arrays.at(name); }
};

Vtu read_vtu(const std::string& path) {
  const std::string xml = read_text(path);
  Vtu v;
  const std::string piece = opening_tag(xml, "Piece");
  v.n_points = std::stol(attribute(piece, "NumberOfPoints"));
  v.n_cells = std::stol(attribute(piece, "NumberOfCells"));
  v.arrays = data_arrays(xml, &v.n_arrays);
  EXPECT_EQ(attribute(opening_tag(xml, "VTKFile"), "type"), "UnstructuredGrid");
  return v;
}

// Checks the invariants ParaView relies on: per-point and per-cell sizes, offsets
// increasing up to the connectivity length, indices inside the point range.
void expect_consistent_cells(const Vtu& v) {
  EXPECT_EQ(v["Points"].components, 3);
  EXPECT_EQ(static_cast<long>(v["Points"].values.size()), 3 * v.n_points);
  const DataArray& offsets = v["offsets"];
  const DataArray& connectivity = v["connectivity"];
  ASSERT_EQ(static_cast<long>(offsets.values.size()), v.n_cells);
  ASSERT_EQ(static_cast<long>(v["types"].values.size()), v.n_cells);
  long previous = 0;
  for (std::size_t c = 0; c < offsets.values.size(); ++c) {
    EXPECT_GT(offsets.integer(c), previous);
    previous = offsets.integer(c);
  }
  EXPECT_EQ(previous, static_cast<long>(connectivity.values.size()));
  for (std::size_t i = 0; i < connectivity.values.size(); ++i) {
    EXPECT_GE(connectivity.integer(i), 0);
    EXPECT_LT(connectivity.integer(i), v.n_points);
  }
  for (const auto& [name, a] : v.arrays) {
    EXPECT_EQ(a.values.size() % a.components, 0u) << name;
  }
}

JointRow joint(int id, const std::string& state_p, const std::string& state_q) {
  JointRow j;
  j.id = id;
  j.p = Vec2(id, 0.0);
  j.q = Vec2(id, 1.0);
  j.length_m = 1.0;
  j.aperture_p_m = 1e-4 * id;
  j.aperture_q_m = 3e-4 * id;
  j.normal_stress_p_Pa = -1e6;
  j.normal_stress_q_Pa = -3e6;
  j.shear_stress_p_Pa = 2e5;
  j.shear_stress_q_Pa = 4e5;
  j.state_p = state_p;
  j.state_q = state_q;
  j.broken = id % 2 == 0;
  j.natural = id % 3 == 0;
  j.fluid = id == 1;
  return j;
}

// --- Joints CSV ------------------------------------------------------------------

TEST_F(OutputTest, CsvHeaderAndRowExact) {
  JointRow j;
  j.id = 7;
  j.p = Vec2(0.1, -2.5);
  j.q = Vec2(1e-3, 3.0);
  j.length_m = 0.1 + 0.2;  // 0.30000000000000004: only full precision keeps the last digit
  j.aperture_p_m = 1e-5;
  j.aperture_q_m = 0.0;
  j.normal_stress_p_Pa = -2.5e6;
  j.normal_stress_q_Pa = 1.5e7;
  j.shear_stress_p_Pa = 123.456;
  j.shear_stress_q_Pa = -1.0 / 3.0;
  j.state_p = "open";
  j.state_q = "locked";
  j.broken = true;
  j.natural = false;
  j.fluid = true;
  j.pressure_p_Pa = 2.5e6;
  j.pressure_q_Pa = 0.0;
  write_joints_csv(path("joints/joints_000001.csv"), {j});

  const std::string text = read_text(path("joints/joints_000001.csv"));
  EXPECT_EQ(text,
            "id,px,py,qx,qy,length,aperture_p,aperture_q,normal_stress_p,normal_stress_q,"
            "shear_stress_p,shear_stress_q,state_p,state_q,broken,natural,fluid,pressure_p,pressure_q\n"
            "7,0.1,-2.5,0.001,3,0.30000000000000004,1e-05,0,-2500000,1.5e+07,123.456,"
            "-0.3333333333333333,open,locked,1,0,1,2500000,0\n");
  // Every number parses back to the identical double.
  EXPECT_EQ(std::strtod("0.30000000000000004", nullptr), 0.1 + 0.2);
  EXPECT_EQ(std::strtod("-0.3333333333333333", nullptr), -1.0 / 3.0);
}

TEST_F(OutputTest, CsvEmptyHasHeaderOnly) {
  write_joints_csv(path("j.csv"), {});
  const std::string text = read_text(path("j.csv"));
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1);
  EXPECT_EQ(text.rfind("id,px,", 0), 0u);
}

// --- Blocks VTU ------------------------------------------------------------------

BlockFrame mixed_frame() {
  // Triangle, unit quad sharing its edge x = 1 with the triangle's corners, pentagon.
  BlockFrame f;
  f.corners = {{0, 0}, {1, 0}, {1, 1},                        // triangle
               {1, 0}, {2, 0}, {2, 1}, {1, 1},                // quad
               {3, 0}, {4, 0}, {4.5, 1}, {3.5, 2}, {2.5, 1}};  // pentagon
  f.corner_offsets = {0, 3, 7, 12};
  for (std::size_t i = 0; i < f.corners.size(); ++i) {
    f.corner_displacement.emplace_back(1e-3 * static_cast<double>(i), -2e-3);
  }
  f.stress = {Eigen::Vector3d(-1e6, -2e6, 3e5), Eigen::Vector3d(1, 2, 3),
              Eigen::Vector3d(0.5, 0.25, -0.125)};
  f.material = {0, 1, 2};
  return f;
}

TEST_F(OutputTest, VtuBlocksCountsOffsetsConnectivity) {
  const BlockFrame f = mixed_frame();
  write_blocks_vtu(path("vtu/blocks_000000.vtu"), f);
  const Vtu v = read_vtu(path("vtu/blocks_000000.vtu"));

  // Corners of neighbouring blocks stay separate points: blocks move independently.
  EXPECT_EQ(v.n_points, 12);
  EXPECT_EQ(v.n_cells, 3);
  EXPECT_EQ(v.n_arrays, 7);  // displacement, stress, material, Points, 3 cell arrays
  expect_consistent_cells(v);

  EXPECT_EQ(v["offsets"].values, (std::vector<std::string>{"3", "7", "12"}));
  EXPECT_EQ(v["types"].values, (std::vector<std::string>{"5", "9", "7"}));
  for (long i = 0; i < 12; ++i) EXPECT_EQ(v["connectivity"].integer(i), i);

  for (std::size_t i = 0; i < f.corners.size(); ++i) {
    EXPECT_EQ(v["Points"].number(3 * i), f.corners[i].x());
    EXPECT_EQ(v["Points"].number(3 * i + 1), f.corners[i].y());
    EXPECT_EQ(v["Points"].number(3 * i + 2), 0.0);
    EXPECT_EQ(v["displacement"].number(3 * i), f.corner_displacement[i].x());
    EXPECT_EQ(v["displacement"].number(3 * i + 2), 0.0);
  }
  EXPECT_EQ(v["displacement"].components, 3);
  EXPECT_EQ(v["stress"].components, 3);
  EXPECT_EQ(v["stress"].type, "Float64");
  ASSERT_EQ(v["stress"].values.size(), 9u);
  EXPECT_EQ(v["stress"].number(0), -1e6);
  EXPECT_EQ(v["stress"].number(8), -0.125);
  EXPECT_EQ(v["material"].type, "Int32");
  EXPECT_EQ(v["material"].values, (std::vector<std::string>{"0", "1", "2"}));
}

TEST_F(OutputTest, VtuBlocksEmptyFrameIsValid) {
  write_blocks_vtu(path("empty.vtu"), BlockFrame{});
  const Vtu v = read_vtu(path("empty.vtu"));
  EXPECT_EQ(v.n_points, 0);
  EXPECT_EQ(v.n_cells, 0);
  EXPECT_EQ(v.n_arrays, 7);
}

TEST_F(OutputTest, VtuBlocksRejectsInconsistentFrame) {
  BlockFrame f = mixed_frame();
  f.stress.pop_back();
  EXPECT_THROW(write_blocks_vtu(path("bad.vtu"), f), std::invalid_argument);
  f = mixed_frame();
  f.corner_offsets.back() = 11;
  EXPECT_THROW(write_blocks_vtu(path("bad.vtu"), f), std::invalid_argument);
  f = mixed_frame();
  f.corner_displacement.pop_back();
  EXPECT_THROW(write_blocks_vtu(path("bad.vtu"), f), std::invalid_argument);
  EXPECT_FALSE(fs::exists(path("bad.vtu")));
}

// --- Joints VTU ------------------------------------------------------------------

TEST_F(OutputTest, VtuJointsStateReductionAndFields) {
  // The more open end wins: open < sliding < locked.
  const std::vector<JointRow> joints{joint(1, "open", "locked"), joint(2, "locked", "sliding"),
                                     joint(3, "locked", "locked"), joint(4, "sliding", "open"),
                                     joint(5, "sliding", "sliding")};
  write_joints_vtu(path("vtu/joints_000000.vtu"), joints);
  const Vtu v = read_vtu(path("vtu/joints_000000.vtu"));

  EXPECT_EQ(v.n_points, 10);
  EXPECT_EQ(v.n_cells, 5);
  EXPECT_EQ(v.n_arrays, 13);  // 9 cell arrays, Points, 3 cell-structure arrays
  expect_consistent_cells(v);
  EXPECT_EQ(v["state"].values, (std::vector<std::string>{"0", "1", "2", "0", "1"}));
  EXPECT_EQ(v["types"].values, (std::vector<std::string>(5, "3")));
  EXPECT_EQ(v["offsets"].values, (std::vector<std::string>{"2", "4", "6", "8", "10"}));
  EXPECT_EQ(v["joint_id"].values, (std::vector<std::string>{"1", "2", "3", "4", "5"}));
  EXPECT_EQ(v["broken"].values, (std::vector<std::string>{"0", "1", "0", "1", "0"}));
  EXPECT_EQ(v["natural"].values, (std::vector<std::string>{"0", "0", "1", "0", "0"}));
  EXPECT_EQ(v["fluid"].values, (std::vector<std::string>{"1", "0", "0", "0", "0"}));
  for (const char* name : {"state", "broken", "natural", "fluid", "joint_id"}) {
    EXPECT_EQ(v[name].type, "Int32") << name;
  }
  for (std::size_t c = 0; c < joints.size(); ++c) {
    const JointRow& j = joints[c];
    EXPECT_DOUBLE_EQ(v["aperture"].number(c), 0.5 * (j.aperture_p_m + j.aperture_q_m));
    EXPECT_DOUBLE_EQ(v["normal_stress"].number(c), -2e6);
    EXPECT_DOUBLE_EQ(v["shear_stress"].number(c), 3e5);
    EXPECT_EQ(v["Points"].number(6 * c), j.p.x());  // p then q, each (x, y, 0)
    EXPECT_EQ(v["Points"].number(6 * c + 4), j.q.y());
  }
}

TEST_F(OutputTest, VtuJointsRejectsUnknownState) {
  EXPECT_THROW(write_joints_vtu(path("j.vtu"), {joint(1, "open", "closed")}),
               std::invalid_argument);
  EXPECT_FALSE(fs::exists(path("j.vtu")));
}

// Optional: full XML well-formedness through Python's standard library, when present.
TEST_F(OutputTest, VtuIsWellFormedXml) {
  if (!fs::exists("/usr/bin/python3")) GTEST_SKIP() << "no /usr/bin/python3";
  write_blocks_vtu(path("b.vtu"), mixed_frame());
  write_joints_vtu(path("j.vtu"), {joint(1, "open", "locked"), joint(2, "sliding", "open")});
  PvdSeries pvd(path("b.pvd"));
  pvd.add(0.0, "b.vtu");
  const std::string command = "/usr/bin/python3 -c \"import sys, xml.etree.ElementTree as E; "
                              "[E.parse(f) for f in sys.argv[1:]]\" '" +
                              path("b.vtu") + "' '" + path("j.vtu") + "' '" + path("b.pvd") + "'";
  EXPECT_EQ(std::system(command.c_str()), 0);
}

// --- PVD -------------------------------------------------------------------------

TEST_F(OutputTest, PvdAfterTwoAdds) {
  PvdSeries pvd(path("blocks.pvd"));
  pvd.add(0.0, "vtu/blocks_000000.vtu");
  pvd.add(0.125, "vtu/blocks_000010.vtu");
  EXPECT_EQ(read_text(path("blocks.pvd")),
            "<?xml version=\"1.0\"?>\n"
            "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
            "  <Collection>\n"
            "    <DataSet timestep=\"0\" part=\"0\" file=\"vtu/blocks_000000.vtu\"/>\n"
            "    <DataSet timestep=\"0.125\" part=\"0\" file=\"vtu/blocks_000010.vtu\"/>\n"
            "  </Collection>\n"
            "</VTKFile>\n");
  EXPECT_EQ(file_names(dir_), std::vector<std::string>{"blocks.pvd"});
}

// --- History CSV -----------------------------------------------------------------

TEST_F(OutputTest, HistoryHeaderRowsFlushedAndSizeChecked) {
  HistoryCsv history(path("history.csv"), {"step", "time", "pressure"});
  history.append({1, 0.1 + 0.2, -2.5e6});
  // Readable before the object is destroyed: every row is flushed.
  EXPECT_EQ(read_text(path("history.csv")), "step,time,pressure\n1,0.30000000000000004,-2500000\n");
  EXPECT_THROW(history.append({1, 2}), std::invalid_argument);
  EXPECT_THROW(history.append({1, 2, 3, 4}), std::invalid_argument);
  history.append({2, 0.5, 0});
  EXPECT_EQ(read_text(path("history.csv")),
            "step,time,pressure\n1,0.30000000000000004,-2500000\n2,0.5,0\n");
}

TEST_F(OutputTest, HistoryTruncatesExistingFile) {
  { HistoryCsv h(path("history.csv"), {"a"}); h.append({1}); h.append({2}); }
  HistoryCsv h(path("history.csv"), {"a"});
  EXPECT_EQ(read_text(path("history.csv")), "a\n");
}

TEST_F(OutputTest, HistoryThrowsWhenFileCannotBeOpened) {
  write_file_atomically(path("plain_file"), "x");
  // A directory cannot be created below a regular file.
  EXPECT_THROW(HistoryCsv(path("plain_file/history.csv"), {"a"}), std::runtime_error);
  fs::create_directories(path("a_directory"));
  EXPECT_THROW(HistoryCsv(path("a_directory"), {"a"}), std::runtime_error);
  EXPECT_THROW(HistoryCsv(path("h.csv"), {"a,b"}), std::invalid_argument);
}

// --- Atomic writes ---------------------------------------------------------------

TEST_F(OutputTest, AtomicWriteCreatesParentsAndLeavesNoTempFiles) {
  write_file_atomically(path("a/b/c.txt"), "first");
  write_file_atomically(path("a/b/c.txt"), "second");  // replaces
  EXPECT_EQ(read_text(path("a/b/c.txt")), "second");
  EXPECT_EQ(file_names(dir_), std::vector<std::string>{"c.txt"});
}

TEST_F(OutputTest, AtomicWriteFailureNamesPathAndLeavesNoTempFiles) {
  // Renaming a file onto a non-empty directory fails after the temporary was written.
  fs::create_directories(path("target/inner"));
  try {
    write_file_atomically(path("target"), "text");
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path("target")), std::string::npos) << e.what();
  }
  EXPECT_TRUE(file_names(dir_).empty());
  for (const auto& e : fs::recursive_directory_iterator(dir_)) {
    EXPECT_EQ(e.path().string().find(".tmp."), std::string::npos) << e.path();
  }

  // Parent path blocked by a regular file: the directory cannot be created.
  write_file_atomically(path("plain"), "x");
  EXPECT_THROW(write_file_atomically(path("plain/child.txt"), "y"), std::runtime_error);
  EXPECT_EQ(file_names(dir_), std::vector<std::string>{"plain"});
}

// --- Performance -----------------------------------------------------------------

TEST_F(OutputTest, PerformanceTwentyThousandBlockFrame) {
  // 20,000 hexagons (a Voronoi-like mesh has about six corners per block).
  constexpr int kBlocks = 20000;
  BlockFrame f;
  f.corner_offsets.push_back(0);
  for (int b = 0; b < kBlocks; ++b) {
    const Vec2 centre(0.0173 * (b % 141), 0.0191 * (b / 141));
    for (int k = 0; k < 6; ++k) {
      const double angle = 1.0471975511965976 * k + 1e-3 * b;
      f.corners.push_back(centre + 0.01 * Vec2(std::cos(angle), std::sin(angle)));
      f.corner_displacement.push_back(1e-5 * Vec2(std::sin(angle + b), std::cos(angle - b)));
    }
    f.corner_offsets.push_back(static_cast<int>(f.corners.size()));
    f.stress.emplace_back(-1.234567e6 * (1 + 1e-4 * b), -2.345678e6, 3.456789e5 / (b + 1));
    f.material.push_back(b % 3);
  }
  const auto start = std::chrono::steady_clock::now();
  write_blocks_vtu(path("big.vtu"), f);
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  const Vtu v = read_vtu(path("big.vtu"));
  EXPECT_EQ(v.n_points, 6 * kBlocks);
  EXPECT_EQ(v.n_cells, kBlocks);
  RecordProperty("write_ms", std::to_string(ms));
  std::printf("20k-block frame (%zu bytes) written in %.1f ms\n",
              static_cast<std::size_t>(fs::file_size(path("big.vtu"))), ms);
  // Target is < 100 ms in Release; the bound here is loose so that Debug or a busy CI
  // machine does not fail, while an accidental O(n^2) or iostream path still would.
  EXPECT_LT(ms, 2000.0);
}

}  // namespace
}  // namespace hfdda::io
