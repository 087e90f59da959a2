// Case files that are malformed or extreme: YAML that would mean something other than
// what was written, values far outside any plausible range, runs too long to make
// sense, lists too large to read, and fields that turn into NaN while running. Each is
// refused with the file, line, key and rule, or read and run correctly.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "io/case_config.hpp"
#include "simulation/field_checks.hpp"
#include "simulation/model.hpp"
#include "simulation/run.hpp"
#include "test_case_support.hpp"

namespace hfdda::io {
namespace {

using namespace case_test;

CaseConfig load(const std::string& text) { return load_case_text(text, "case.yaml"); }

// --- YAML that means something else -----------------------------------------

TEST(CaseFileHostile, UnclosedQuoteIsRefused) {
  // yaml-cpp reads the rest of the file into the title and runs the default case.
  expect_text_error("title: \"abc\nmesh: {cell_size: 2}\n", 1, "(syntax)", "unclosed quote");
  expect_text_error("title: x\nmaterials:\n  - {name: 'rock}\n", 3, "(syntax)", "unclosed quote");
}

TEST(CaseFileHostile, QuotesThatAreNotUnclosedStillRead) {
  EXPECT_EQ(load("title: Griffith's crack\n").title, "Griffith's crack");
  EXPECT_EQ(load("title: a-'b\n").title, "a-'b");
  EXPECT_EQ(load("{\"title\":\"json\"}\n").title, "json");
  EXPECT_EQ(load("title: 'it''s \"here\"'  # comment's\n").title, "it's \"here\"");
  EXPECT_EQ(load("title: |\n  a \"quote' left open\n").title, "a \"quote' left open\n");
  const CaseConfig c = load(
      "domain:\n  outer: {xmin: -10, xmax: 10,\n          ymin: -5, ymax: 5}\nmesh: {cell_size: 2}\n");
  EXPECT_EQ(c.domain.outer.ymax, 5);
}

TEST(CaseFileHostile, SecondDocumentIsRefused) {
  expect_text_error("title: a\n---\ntitle: b\n", 2, "(document)", "second YAML document");
  EXPECT_EQ(load("---\ntitle: a\n").title, "a");  // a leading marker is fine
}

TEST(CaseFileHostile, YamlDirectiveStartsTheOneDocument) {
  EXPECT_EQ(load("%YAML 1.2\n---\ntitle: a\n").title, "a");
  EXPECT_EQ(load("# a comment first\n%YAML 1.1\n---\ntitle: b\n").title, "b");
  expect_text_error("%YAML 1.2\n---\ntitle: a\n---\ntitle: b\n", 4, "(document)", "second YAML document");
  expect_text_error("%YAML 1.2\n---\n", 0, "(document)", "empty case file");
}

TEST(CaseFileHostile, NulBytesAreRefused) {
  // A "\0" escape cut the extends path at the NUL: "base.yaml\0junk" read base.yaml.
  expect_text_error("title: x\nextends: \"base.yaml\\0junk\"\n", 2, "extends",
                    "holds a NUL byte (\\0) at character 10");
  expect_text_error("title: \"a\\0b\"\n", 1, "title", "NUL byte");
  expect_text_error(std::string("title: x\nextends: base.yaml\0junk\n", 33), 2, "(syntax)",
                    "a NUL byte (0x00) at character 19");
}

TEST(CaseFileHostile, DocumentEndInTheMiddleIsRefused) {
  expect_text_error("title: a\n...\ntime: {dt: 0.5}\n", 2, "(document)", "'...' ends the YAML document");
  EXPECT_EQ(load("title: a\n...\n# trailing comment\n").title, "a");
}

TEST(CaseFileHostile, EmptyFileIsRefused) {
  expect_text_error("", 0, "(document)", "empty case file");
  expect_text_error("# nothing but a comment\n\n", 0, "(document)", "empty case file");
  expect_text_error("---\n", 0, "(document)", "empty case file");
  expect_text_error("~\n", 0, "(document)", "empty case file");
}

TEST(CaseFileHostile, TagsAreRefused) {
  expect_text_error("title: !!str 1.0\n", 1, "title", "YAML tags such as '!!str' are not allowed");
  expect_text_error("time:\n  dt: !!float 1\n", 2, "time.dt", "'!!float'");
  expect_text_error("mesh: !custom {cell_size: 2}\n", 1, "mesh", "'!custom'");
}

TEST(CaseFileHostile, AnchorsAndAliasesAreRefused) {
  expect_text_error("a: &x [1, 2]\n", 1, "(syntax)", "anchors and aliases ('&')");
  expect_text_error("title: x\nb: [*x, *x]\n", 2, "(syntax)", "('*')");
  EXPECT_EQ(load("title: R&D *draft*\n").title, "R&D *draft*");
}

TEST(CaseFileHostile, CarriageReturnLineEndingsAreRead) {
  for (const std::string eol : {"\r", "\r\n"}) {
    const CaseConfig c = load("title: cr" + eol + "time:" + eol + "  dt: 0.5" + eol +
                                        "  end_time: 2" + eol + "mesh: {cell_size: 2}" + eol);
    EXPECT_EQ(c.title, "cr");
    EXPECT_EQ(c.time.dt_s, 0.5);
    EXPECT_EQ(c.time.end_time_s, 2.0);
    EXPECT_EQ(c.mesh.cell_size_m, 2.0);
  }
  expect_text_error("title: x\rtime:\r  dt: 0\r", 3, "time.dt", "must be in (0, 1e10]");
}

TEST(CaseFileHostile, DeepNestingIsRefusedBeforeParsing) {
  // A million brackets would overflow the stack of the recursive YAML parser.
  const std::string flow = "title: " + std::string(1000000, '[') + std::string(1000000, ']') + "\n";
  expect_text_error(flow, 1, "(document)", "nesting too deep: more than 16 levels");
  std::string block;
  for (int i = 0; i < 40; ++i) block += std::string(i, ' ') + "k" + std::to_string(i) + ":\n";
  expect_text_error(block, 17, "(document)", "nesting too deep");
  std::string dashes = "fixed_points:\n  " ;
  for (int i = 0; i < 30; ++i) dashes += "- ";
  expect_text_error(dashes + "1\n", 2, "(document)", "nesting too deep");
}

TEST(CaseFileHostile, KeyTooLongIsRefused) {
  const std::string key(300, 'k');
  const auto error = error_of_text("title: x\n" + key + ": 1\n");
  ASSERT_TRUE(error);
  EXPECT_EQ(error->line(), 2);
  EXPECT_NE(error->rule().find("key too long: 300 characters; at most 64"), std::string::npos);
  EXPECT_LE(error->key().size(), 40u);
}

TEST(CaseFileHostile, DecimalCommaIsNamed) {
  expect_text_error("time:\n  dt: 1,5\n", 2, "time.dt", "decimal comma? write 1.5 (got '1,5')");
  expect_text_error("numerics:\n  max_step_cuts: 3,0\n", 2, "numerics.max_step_cuts", "decimal comma?");
  expect_text_error("time:\n  dt: 1,5,2\n", 2, "time.dt", "expected a finite number (got '1,5,2')");
  // In { } and [ ] YAML splits 1,5 in two: the value 1 (out of range here) and a key 5.
  expect_text_error("materials:\n  - {youngs_modulus: 1,5}\n", 2, "materials[0].youngs_modulus",
                    "decimal comma? write 1.5 (got '1,5', which a { } map reads as the value 1 and a key '5')");
  expect_text_error("far_field: {sides: [top], syy: -1,5}\n", 1, "far_field.syy", "decimal comma? write -1.5");
  expect_text_error("point_loads:\n  - {at: [0, 0], force: [1,5, 2]}\n", 2, "point_loads[0].force",
                    "decimal comma? '1,5' is two items in [ ]: write 1.5");
  // Not a split number: a blank after the comma, or a key that has a value.
  expect_text_error("materials:\n  - {density: 1, 5}\n", 2, "materials[0].5", "unknown key");
  expect_text_error("materials:\n  - {density: 1,5: 2}\n", 2, "materials[0].5", "unknown key");
  EXPECT_EQ(load("fixed_points: [[0,0], [1,1]]\n").fixed_points.size(), 2u);
}

TEST(CaseFileHostile, InvalidUtf8IsRefusedUpFront) {
  expect_text_error("title: caf\xe9 noir\n", 1, "title", "is not valid UTF-8 text (byte 0xE9 at character 4)");
  expect_text_error("materials:\n  - {name: \"r\xc3\"}\n", 2, "materials[0].name", "not valid UTF-8");
  EXPECT_EQ(load("title: caf\xc3\xa9\n").title, "caf\xc3\xa9");
}

TEST(CaseFileHostile, EchoedValuesAreCut) {
  const std::string word(500, 'w');
  const auto error = error_of_text("mesh: {type: " + word + "}\n");
  ASSERT_TRUE(error);
  EXPECT_NE(error->rule().find(std::string(77, 'w') + "...'"), std::string::npos) << error->rule();
  EXPECT_EQ(error->rule().find(std::string(81, 'w')), std::string::npos);
  const auto missing = error_of_text("extends: " + std::string(300, 'b') + ".yaml\n");
  ASSERT_TRUE(missing);
  EXPECT_LT(missing->rule().size(), 150u) << missing->rule();
}

// --- Plausible bounds ---------------------------------------------------------

TEST(CaseFileHostile, PhysicalParametersHavePlausibleBounds) {
  expect_text_error("materials:\n  - {youngs_modulus: 1e308}\n", 2, "materials[0].youngs_modulus",
                    "must be in [1000, 1e13] (got 1e308)");
  expect_text_error("contact: {normal_stiffness: 1e308}\n", 1, "contact.normal_stiffness",
                    "must be in [1, 1e6]");
  expect_text_error("far_field: {syy: -1e308}\n", 1, "far_field.syy", "must be in [-1e10, 1e10]");
  expect_text_error("far_field: {sxx: 1e200}\n", 1, "far_field.sxx", "must be in [-1e10, 1e10]");
  expect_text_error("fractures:\n  - {from: [0, 0], to: [1, 0], pressure: 1e200}\n", 2,
                    "fractures[0].pressure", "must be in [0, 1e10]");
  expect_text_error("body_force: [0, 1e300]\n", 1, "body_force[1]", "must be in [-1e7, 1e7]");
  expect_text_error("fluid: {bulk_modulus: 1e300}\n", 1, "fluid.bulk_modulus", "[1e5, 1e13]");
  expect_text_error("domain:\n  outer: {xmin: -1e300, xmax: 1, ymin: 0, ymax: 1}\n", 2,
                    "domain.outer.xmin", "[-1e7, 1e7]");
}

TEST(CaseFileHostile, ModuliHavePlausibleLowerBounds) {
  // Each value below stopped a run of fuzz/corpus/small_fluid.yaml (K not positive
  // definite, singular mass-balance Jacobian) or crashed it (shear stiffness 1e-30).
  expect_text_error("materials:\n  - {youngs_modulus: 1e-300}\n", 2, "materials[0].youngs_modulus",
                    "must be in [1000, 1e13] (got 1e-300)");
  expect_text_error("contact: {normal_stiffness: 1e-300}\n", 1, "contact.normal_stiffness", "[1, 1e6]");
  expect_text_error("contact: {shear_stiffness: 1e-30}\n", 1, "contact.shear_stiffness", "[1, 1e6]");
  expect_text_error("contact: {fixed_point_stiffness: 0.5}\n", 1, "contact.fixed_point_stiffness", "[1, 1e6]");
  expect_text_error("fluid: {bulk_modulus: 1e-300}\n", 1, "fluid.bulk_modulus", "[1e5, 1e13]");
  expect_text_error("fluid: {viscosity: 1e-300}\n", 1, "fluid.viscosity", "[1e-6, 1e6]");
  expect_text_error("fluid: {density: 1e-300}\n", 1, "fluid.density", "[0.01, 1e5]");
  // The bounds themselves are allowed.
  const CaseConfig c = load(
      "materials:\n  - {youngs_modulus: 1e3}\ncontact: {normal_stiffness: 1, shear_stiffness: 1, "
      "fixed_point_stiffness: 1}\nfluid: {bulk_modulus: 1e5, viscosity: 1e-6, density: 0.01}\n"
      "fractures:\n  - {from: [0, 0], to: [1, 0], initially_open: true, fluid_filled: true}\n");
  EXPECT_EQ(c.materials[0].youngs_modulus_Pa, 1e3);
  EXPECT_EQ(c.fluid->bulk_modulus_Pa, 1e5);
}

// --- Keys that would be read and then do nothing ----------------------------------

TEST(CaseFileHostile, FarFieldStressNeedsASide) {
  expect_text_error("title: x\nfar_field: {syy: -5e6, sides: []}\n", 2, "far_field.sides",
                    "is empty, so the far-field stress (sxx 0, syy -5e6, sxy 0) would act on no side");
  expect_text_error("far_field:\n  sxx: -5e6\n", 2, "far_field.sxx",
                    "acts only on the left and right sides (the traction is sigma . n), but far_field.sides is "
                    "[top, bottom] (the default), with neither");
  expect_text_error("far_field:\n  sides: [left]\n  syy: -5e6\n", 3, "far_field.syy",
                    "far_field.sides is [left], with neither");
  expect_text_error("load_ramp: {syy: 1, increment: 1e4, maximum: 1e6, sides: []}\n", 1, "load_ramp.sides",
                    "is empty, so the ramp's stress pattern");
  // What does act: shear on any side, in situ on all four, no stress on none.
  EXPECT_NO_THROW(load("far_field: {sxy: 1e6, sides: [top]}\n"));
  EXPECT_NO_THROW(load("far_field: {sxx: -5e6, syy: -5e6, in_situ: true, sides: []}\n"));
  EXPECT_NO_THROW(load("far_field: {sides: []}\n"));
}

TEST(CaseFileHostile, PressureNeedsJointsThatOpen) {
  expect_text_error("fractures:\n  - {from: [-2, 0], to: [2, 0], pressure: 1e6}\n", 2, "fractures[0].pressure",
                    "acts only on open joints: on a fracture without initially_open: true, only on joints that "
                    "break open during the run; a joint breaks only next to an open one, and no fracture is "
                    "initially open");
  expect_text_error("joints: {breakable: false}\nfractures:\n  - {from: [-2, 0], to: [0, 0], initially_open: true}\n"
                    "  - {from: [0, 0], to: [2, 0], pressure: 1e6}\n",
                    4, "fractures[1].pressure", "(joints.breakable: false)");
  // An initially open fracture, or a breakable path from one (its joints take the
  // pressure as they break: the bonds break from the open crack's tip).
  EXPECT_NO_THROW(load("fractures:\n  - {from: [-2, 0], to: [2, 0], initially_open: true, pressure: 1e6}\n"));
  EXPECT_NO_THROW(load("fractures:\n  - {from: [-2, 0], to: [0, 0], initially_open: true, pressure: 1e6}\n"
                       "  - {from: [0, 0], to: [2, 0], pressure: 1e6}\n"));
}

TEST(CaseFileHostile, SegmentLengthIsOneTheMesherHonours) {
  expect_text_error("fractures:\n  - {from: [-2, 0], to: [2, 0], segment_length: 0.001}\n", 2,
                    "fractures[0].segment_length", "is only used by a Delaunay mesh (mesh.type: delaunay)");
  const std::string delaunay =
      "domain:\n  outer: {xmin: -8, xmax: 8, ymin: -8, ymax: 8}\n  inner: {xmin: -4, xmax: 4, ymin: -2, ymax: 2}\n"
      "mesh: {type: delaunay, max_area_inner: 0.25, max_area_outer: 4}\nfractures:\n";
  expect_text_error(delaunay + "  - {from: [-2, 0], to: [2, 0], segment_length: 0.004}\n", 6,
                    "fractures[0].segment_length",
                    "must be at least 0.01 of the mesh size it meets, sqrt(mesh.max_area_inner) = 0.5 m, i.e. >= "
                    "0.005 m (got 0.004)");
  EXPECT_NO_THROW(load(delaunay + "  - {from: [-2, 0], to: [2, 0], segment_length: 0.005}\n"));
  // Out of the inner rectangle the pieces meet the coarser triangles.
  expect_text_error(delaunay + "  - {from: [-2, 0], to: [6, 0], segment_length: 0.01}\n", 6,
                    "fractures[0].segment_length", "sqrt(mesh.max_area_outer) = 2 m, i.e. >= 0.02 m");
  // Pieces count towards the cell limit.
  expect_text_error(
      "domain: {outer: {xmin: -5e6, xmax: 5e6, ymin: -1, ymax: 1}}\nmesh: {type: delaunay, max_area_inner: 1e4}\n"
      "fractures:\n  - {from: [-5e6, 0], to: [5e6, 0], segment_length: 1}\n",
      4, "fractures[0].segment_length", "of them along the fracture pieces of segment_length); at most 1e7");
}

TEST(CaseFileHostile, EveryNumberIsFinite) {
  expect_text_error("far_field: {syy: .nan}\n", 1, "far_field.syy", "expected a finite number");
  expect_text_error("materials:\n  - {density: -.inf}\n", 2, "materials[0].density", "finite");
  expect_text_error("point_loads:\n  - {force: [.inf, 0]}\n", 2, "point_loads[0].force", "finite");
}

TEST(CaseFileHostile, LengthsStayWithinTheDomain) {
  expect_text_error("mesh:\n  cell_size: 1e6\n", 2, "mesh.cell_size",
                    "must be <= the larger side of domain.outer, 100 m (got 1e6)");
  expect_text_error("mesh:\n  cell_size: 1e-4\n", 2, "mesh.cell_size", "would make about 1e12 cells");
  expect_text_error("mesh:\n  type: delaunay\n  max_area_inner: 1e-9\n", 3, "mesh.max_area_inner",
                    "cells; at most 1e7");
  expect_text_error("contact:\n  vertex_vertex_activation: 1e5\n", 2, "contact.vertex_vertex_activation",
                    "<= the larger side");
}

// --- Time and counts ------------------------------------------------------------

TEST(CaseFileHostile, StepCountIsBounded) {
  expect_text_error("time:\n  dt: 1\n  end_time: 4294967297\n", 3, "time.end_time",
                    "gives 4294967297 time steps");
  expect_text_error("time:\n  dt: 1e-300\n", 2, "time.dt", "at most 1e7 are allowed");
}

TEST(CaseFileHostile, EndTimeIsAWholeNumberOfSteps) {
  expect_text_error("time:\n  dt: 1\n  end_time: 2.5\n", 3, "time.end_time",
                    "is not a whole number of time steps (end_time 2.5 s, dt 1 s: 2.5 steps)");
  expect_text_error("time:\n  dt: 1\n  end_time: 2.5\n", 3, "time.end_time", "e.g. 2 or 3 s");
  EXPECT_EQ(load("time: {dt: 0.1, end_time: 0.3}\n").time.end_time_s, 0.3);  // rounding
}

TEST(CaseFileHostile, IntegersHaveUpperBounds) {
  expect_text_error("numerics: {max_step_cuts: 2147483647}\n", 1, "numerics.max_step_cuts",
                    "must be in [0, 30]");
  expect_text_error("numerics: {max_alm_iterations: 2000000}\n", 1, "numerics.max_alm_iterations",
                    "must be in [1, 1e6]");
  expect_text_error("output: {every_steps: 100000000}\n", 1, "output.every_steps", "[0, 1e7]");
  expect_text_error("numerics: {max_coupling_iterations: 99999999999}\n", 1,
                    "numerics.max_coupling_iterations", "is far too large (got '99999999999'");
}

TEST(CaseFileHostile, HugeListsAreRefused) {
  std::string points = "fixed_points: [";
  for (int i = 0; i < 10001; ++i) points += "[0, 0], ";
  points += "[0, 0]]\n";
  expect_text_error(points, 1, "fixed_points", "has 10002 items; at most 10000 are allowed");
  std::string probes = "probes:\n";
  for (int i = 0; i < 10001; ++i) probes += "  - {name: p" + std::to_string(i) + ", at: [0, 0]}\n";
  expect_text_error(probes, 2, "probes", "at most 10000");
  std::string many = "title: x\nfractures: [";
  for (int i = 0; i < 150000; ++i) many += "1, ";
  expect_text_error(many + "1]\n", 2, "fractures", "a list of 150001 items; at most 100000");
  // Millions of items in a file under 4 MiB: refused by the text scan before yaml-cpp
  // builds its nodes (it spent about 1 GB on two million), at the line where the
  // count passes the limit.
  std::string million = "title: x\nfixed_points: [";
  for (int i = 0; i < 1000000; ++i) million += "0,";
  expect_text_error(million + "0]\n", 2, "(file)", "more than 400000 YAML values");
  const std::string huge = "title: x\n# " + std::string(5u << 20, 'x') + "\n";
  expect_text_error(huge, 0, "(file)", "at most 4194304 bytes");
}

// --- Run time: non-finite fields stop the run -----------------------------------

TEST(CaseFileHostile, NonFiniteFieldsStopTheRun) {
  // Built past the input checks: a modulus no case file may give, which overflows.
  CaseConfig config = load(
      "title: overflow\ndomain:\n  outer: {xmin: -4, xmax: 4, ymin: -4, ymax: 4}\n"
      "mesh: {cell_size: 2}\nfar_field: {syy: -1e6}\ntime: {dt: 1, end_time: 3}\n"
      "output: {vtu: false}\n");
  config.far_field.syy_Pa = -1e308;
  config.far_field.sxx_Pa = 1e308;
  simulation::Model model = simulation::build_model(config);
  simulation::RunOptions options;
  options.output_dir = (std::filesystem::path(testing::TempDir()) / "hfdda_hostile_nan").string();
  options.quiet = true;
  std::filesystem::remove_all(options.output_dir);
  const simulation::RunResult result = simulation::run(model, options);
  EXPECT_FALSE(result.completed);
  EXPECT_NE(result.message.find("is not a finite number"), std::string::npos) << result.message;
  EXPECT_NE(result.message.find("after step 1"), std::string::npos) << result.message;
  EXPECT_TRUE(std::filesystem::exists(options.output_dir + "/summary.json"));
  EXPECT_TRUE(std::filesystem::exists(options.output_dir + "/history.csv"));
}

TEST(CaseFileHostile, FiniteFieldsPass) {
  simulation::Model model = simulation::build_model(load(
      "title: fine\ndomain:\n  outer: {xmin: -4, xmax: 4, ymin: -4, ymax: 4}\nmesh: {cell_size: 2}\n"));
  EXPECT_NO_THROW(simulation::check_fields_finite(*model.system, model.flow.get(), 0));
}

}  // namespace
}  // namespace hfdda::io
