// `fracture_maps`: natural fractures read from CSV files of segments
// (solver/io/fracture_maps.hpp): rows become fractures, bad rows are errors naming the
// CSV file and line, tens of thousands of rows load, and a map gives the model the same
// joints as the equivalent `fractures:` list.

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "core/errors.hpp"
#include "io/case_config.hpp"
#include "simulation/checkpoint.hpp"
#include "simulation/model.hpp"

namespace hfdda::io {
namespace {

namespace fs = std::filesystem;

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("hfdda_maps_" + std::to_string(::getpid()));
  TempDir() { fs::create_directories(path); }
  ~TempDir() { fs::remove_all(path); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(path / name) << text;
    return (path / name).string();
  }
};

const char* kCase = R"(
title: map
domain: {outer: {xmin: -10, xmax: 10, ymin: -10, ymax: 10}}
mesh: {type: delaunay, max_area_inner: 2.0}
fracture_maps:
  - {name: nf, file: map.csv, segment_length: 1.0, friction_angle: 35, hydraulic_width: 1.0e-6}
)";

TEST(FractureMaps, RowsBecomeNaturalFractures) {
  TempDir dir;
  dir.write("map.csv", "x1,y1,x2,y2,set,cohesion\n-5,0,5,0,J1,\n0,-5,0,5,J2,2e6\n");
  const CaseConfig c = load_case_file(dir.write("case.yaml", kCase));
  ASSERT_EQ(c.fractures.size(), 2u);
  EXPECT_EQ(c.fractures[0].name, "nf.1");
  EXPECT_TRUE(c.fractures[0].natural);
  EXPECT_EQ(*c.fractures[0].friction_angle_deg, 35.0);
  EXPECT_FALSE(c.fractures[0].cohesion_Pa.has_value());
  EXPECT_EQ(*c.fractures[1].cohesion_Pa, 2e6);  // the row's own value
  EXPECT_EQ(c.fractures[1].to, Vec2(0, 5));
}

void expect_csv_error(const std::string& csv, int line, const std::string& key, const std::string& rule) {
  TempDir dir;
  const std::string path = dir.write("map.csv", csv);
  try {
    load_case_file(dir.write("case.yaml", kCase));
    ADD_FAILURE() << "accepted: " << csv;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path);
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_EQ(e.key(), key) << e.what();
    EXPECT_NE(std::string(e.what()).find(rule), std::string::npos) << e.what();
  }
}

TEST(FractureMaps, BadRowsNameTheCsvLine) {
  expect_csv_error("x1,y1,x2\n0,0,1\n", 1, "(header)", "missing column 'y2'");
  expect_csv_error("x1,y1,x2,y2,dip\n", 1, "(header)", "unknown column 'dip'");
  expect_csv_error("x1,y1,x2,y2\n0,0,1,1\n\n2,2,2,2\n", 4, "x2", "zero-length");
  expect_csv_error("x1,y1,x2,y2\n0,0,1,1\n1,1,0,0\n", 3, "x1", "duplicate of the segment on line 2");
  expect_csv_error("x1,y1,x2,y2\n0,0,1,1\n11,0,12,1\n", 3, "x1", "outside domain.outer");
  expect_csv_error("x1,y1,x2,y2\n0,0,1,1\n10,-12,10,-11\n", 3, "x1", "outside domain.outer");
  expect_csv_error("x1,y1,x2,y2\n0,0,1,1x\n", 2, "y2", "not a finite number");
  expect_csv_error("x1,y1,x2,y2\n0,0,1\n", 2, "(row)", "3 cells");
  expect_csv_error("x1,y1,x2,y2\n", 1, "(rows)", "no segment");
}

TEST(FractureMaps, TwentyThousandRowsLoadQuickly) {
  TempDir dir;
  std::string csv = "x1,y1,x2,y2\n";
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-9.0, 9.0);
  for (int i = 0; i < 20000; ++i)
    csv += std::to_string(u(rng)) + "," + std::to_string(u(rng)) + "," + std::to_string(u(rng)) + "," +
           std::to_string(u(rng)) + "\n";
  dir.write("map.csv", csv);
  const auto start = std::chrono::steady_clock::now();
  const CaseConfig c = load_case_file(dir.write("case.yaml", kCase));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(c.fractures.size(), 20000u);
  EXPECT_LT(seconds, 1.0);
}

TEST(FractureMaps, SameJointsAsTheFracturesList) {
  // Two crossing natural fractures, once as a map and once as `fractures:`: the same mesh
  // and the same natural joints with the same hydraulic width.
  TempDir dir;
  dir.write("map.csv", "x1,y1,x2,y2\n-6,0.5,6,0.5\n-2.25,-6,-2.25,6\n");
  const std::string listed = std::string(R"(
title: list
domain: {outer: {xmin: -10, xmax: 10, ymin: -10, ymax: 10}}
mesh: {type: delaunay, max_area_inner: 2.0}
fractures:
  - {name: a, from: [-6, 0.5], to: [6, 0.5], natural: true, segment_length: 1.0, friction_angle: 35, hydraulic_width: 1.0e-6}
  - {name: b, from: [-2.25, -6], to: [-2.25, 6], natural: true, segment_length: 1.0, friction_angle: 35, hydraulic_width: 1.0e-6}
)");
  const simulation::Model from_map = simulation::build_model(load_case_file(dir.write("case.yaml", kCase)));
  const simulation::Model from_list = simulation::build_model(load_case_file(dir.write("list.yaml", listed)));
  const auto& jm = from_map.system->mesh().joints;
  const auto& jl = from_list.system->mesh().joints;
  ASSERT_EQ(jm.size(), jl.size());
  int natural = 0;
  for (std::size_t j = 0; j < jm.size(); ++j) {
    EXPECT_EQ(jm[j].properties.natural, jl[j].properties.natural);
    EXPECT_EQ(jm[j].properties.hydraulic_width_m, jl[j].properties.hydraulic_width_m);
    natural += jm[j].properties.natural;
  }
  EXPECT_GE(natural, 24);  // 12 m + 12 m of joints no longer than 1 m
}

TEST(FractureMaps, EveryFractureOfADenseMapOwnsItsJoints) {
  // 400 random segments crossing each other, some ends a digitising error from another
  // segment: the joints of each fracture come from its constraint through meshing, so
  // every fracture is made of joints whose length is its own (as snapped).
  TempDir dir;
  std::string csv = "x1,y1,x2,y2\n";
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> centre(-8.0, 8.0), angle(0.0, 3.14159), length(0.5, 2.5);
  for (int i = 0; i < 400; ++i) {
    const double cx = centre(rng), cy = centre(rng), a = angle(rng), l = length(rng);
    csv += std::to_string(cx - 0.5 * l * std::cos(a)) + "," + std::to_string(cy - 0.5 * l * std::sin(a)) + "," +
           std::to_string(cx + 0.5 * l * std::cos(a)) + "," + std::to_string(cy + 0.5 * l * std::sin(a)) + "\n";
  }
  csv += "-9,9,9,9\n-3,9.000003,-3,5\n";  // an end 3 um above the fracture before it: snapped
  dir.write("map.csv", csv);
  const CaseConfig c = load_case_file(dir.write("case.yaml", kCase));
  const simulation::Model model = simulation::build_model(c);
  const auto& mesh = model.system->mesh();
  ASSERT_TRUE(mesh.has_feature_edges);
  EXPECT_GE(mesh.feature_snaps.size(), 1u);
  std::vector<double> owned(c.fractures.size(), 0.0);
  for (const auto& e : mesh.feature_edges) owned[e.feature] += (mesh.points[e.point_q] - mesh.points[e.point_p]).norm();
  for (std::size_t f = 0; f < c.fractures.size(); ++f)
    EXPECT_NEAR(owned[f], (c.fractures[f].to - c.fractures[f].from).norm(), 1e-5) << "fracture " << f;
  int natural = 0;
  for (const auto& j : mesh.joints) natural += j.properties.natural;
  EXPECT_GE(natural, 400);
}

TEST(FractureMaps, RowsReachingPastTheDomainAreCutAtItsSide) {
  // An outcrop map larger than the model: each row keeps its part inside domain.outer,
  // its cut end exactly on the side, and the cut is reported; rows inside are unchanged.
  TempDir dir;
  dir.write("map.csv", "x1,y1,x2,y2\n-14,0,6,0\n3,-4,3,4\n-5,5,15,15\n");
  const CaseConfig c = load_case_file(dir.write("case.yaml", kCase));
  ASSERT_EQ(c.fractures.size(), 3u);
  EXPECT_EQ(c.fractures[0].from, Vec2(-10, 0));
  EXPECT_EQ(c.fractures[0].to, Vec2(6, 0));
  EXPECT_NEAR(c.fractures[0].clipped_length_m, 4.0, 1e-12);
  EXPECT_EQ(c.fractures[1].clipped_length_m, 0.0);
  EXPECT_EQ(c.fractures[2].to, Vec2(5, 10));  // y = 7.5 + x / 2 leaves through y = 10 at x = 5
  EXPECT_NEAR(c.fractures[2].clipped_length_m, std::hypot(20.0, 10.0) - std::hypot(10.0, 5.0), 1e-12);
  const simulation::Model model = simulation::build_model(c);
  const std::string note = simulation::fracture_adjustments_note(c, model.system->mesh());
  EXPECT_NE(note.find("2 fracture-map row(s) cut at domain.outer"), std::string::npos) << note;
}

TEST(FractureMaps, NearMissesWithinTheStatedToleranceAreSnappedAndNamed) {
  // A digitised row that stops 4 mm short of another: left apart at the default
  // tolerance (rounding only), made to meet at a stated 1 cm, and reported by name.
  TempDir dir;
  dir.write("map.csv", "x1,y1,x2,y2\n-6,0,6,0\n2,-5,2,-0.004\n");
  const simulation::Model apart = simulation::build_model(load_case_file(dir.write("case.yaml", kCase)));
  EXPECT_TRUE(apart.system->mesh().feature_snaps.empty());
  const CaseConfig c = load_case_file(dir.write("stated.yaml", "extends: case.yaml\nmesh: {snap_tolerance: 0.01}\n"));
  const simulation::Model met = simulation::build_model(c);
  const auto& snaps = met.system->mesh().feature_snaps;
  ASSERT_EQ(snaps.size(), 1u);
  EXPECT_EQ(snaps[0].feature, "nf.2");
  EXPECT_EQ(snaps[0].to, Vec2(2, 0));
  EXPECT_NEAR(snaps[0].moved_m, 0.004, 1e-12);
  const std::string note = simulation::fracture_adjustments_note(c, met.system->mesh());
  EXPECT_NE(note.find("1 fracture end(s) snapped"), std::string::npos) << note;
  EXPECT_NE(note.find("nf.2"), std::string::npos) << note;
}

TEST(FractureMaps, TheMapIsPartOfTheRestartFingerprint) {
  // A restart checks that the case is the one checkpointed: a changed CSV value that does
  // not move any joint (one row's cohesion) still changes the fingerprint.
  TempDir dir;
  dir.write("map.csv", "x1,y1,x2,y2,cohesion\n-5,0,5,0,1e6\n");
  const std::string case_path = dir.write("case.yaml", kCase);
  const std::uint64_t before = simulation::case_fingerprint(simulation::build_model(load_case_file(case_path)));
  EXPECT_EQ(before, simulation::case_fingerprint(simulation::build_model(load_case_file(case_path))));
  dir.write("map.csv", "x1,y1,x2,y2,cohesion\n-5,0,5,0,2e6\n");
  EXPECT_NE(before, simulation::case_fingerprint(simulation::build_model(load_case_file(case_path))));
}

}  // namespace
}  // namespace hfdda::io
