// Case-file fluid section, injections, probes and the coupling numerics: values,
// defaults, extends merging and errors.

#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

#include "io/case_config.hpp"
#include "test_case_support.hpp"

namespace hfdda::io {
namespace {

using namespace case_test;

/// A minimal fluid case (one fluid-filled fracture and one injection) with `extra` appended.
std::string fluid_case(const std::string& extra = "") {
  return "fractures:\n"
         "  - {from: [-1, 0], to: [1, 0], initially_open: true, fluid_filled: true}\n"
         "fluid: {}\n"
         "injections:\n"
         "  - {at: [0, 0], mass_rate: 1}\n" +
         extra;
}

TEST(CaseFileFluid, FullFileHasExpectedValues) {
  const CaseConfig c = load_case_file(kCases + "fluid_full.yaml");
  ASSERT_EQ(c.fractures.size(), 3u);
  EXPECT_TRUE(c.fractures[0].initially_open);
  EXPECT_TRUE(c.fractures[0].fluid_filled);
  EXPECT_EQ(c.fractures[0].initial_width_m, 2e-6);
  EXPECT_EQ(c.fractures[0].line, 4);
  EXPECT_TRUE(c.fractures[1].fluid_filled);
  EXPECT_EQ(c.fractures[1].initial_width_m, 0.0);
  EXPECT_EQ(c.fractures[1].line, 5);
  EXPECT_FALSE(c.fractures[2].fluid_filled);

  ASSERT_TRUE(c.fluid.has_value());
  EXPECT_EQ(c.fluid->density_kg_m3, 1050);
  EXPECT_EQ(c.fluid->bulk_modulus_Pa, 2.0e9);
  EXPECT_EQ(c.fluid->viscosity_Pa_s, 0.02);
  EXPECT_EQ(c.fluid->reference_pressure_Pa, 1e5);
  EXPECT_EQ(c.fluid->leak_off_coefficient_m_sqrt_s, 2e-5);

  ASSERT_EQ(c.injections.size(), 2u);
  EXPECT_EQ(c.injections[0].name, "well");
  EXPECT_EQ(c.injections[0].at, Vec2(0, 0));
  EXPECT_EQ(c.injections[0].mass_rate_kg_s, 4.0);
  EXPECT_EQ(c.injections[0].start_time_s, 5);
  EXPECT_EQ(c.injections[0].line, 18);
  EXPECT_EQ(c.injections[1].name, "injection");  // item default
  EXPECT_EQ(c.injections[1].at, Vec2(10, -2));
  EXPECT_EQ(c.injections[1].mass_rate_kg_s, 0.5);
  EXPECT_EQ(c.injections[1].start_time_s, 0);
  EXPECT_EQ(c.injections[1].line, 19);

  ASSERT_EQ(c.probes.size(), 2u);
  EXPECT_EQ(c.probes[0].name, "inlet");
  EXPECT_EQ(c.probes[0].at, Vec2(0, 0));
  EXPECT_EQ(c.probes[0].line, 22);
  EXPECT_EQ(c.probes[1].name, "Tip_2");
  EXPECT_EQ(c.probes[1].at, Vec2(8, 0.5));
  EXPECT_EQ(c.probes[1].line, 23);

  EXPECT_EQ(c.numerics.min_width_main_m, 1e-6);
  EXPECT_EQ(c.numerics.min_width_tip_m, 2e-7);
  EXPECT_EQ(c.numerics.max_closing_fraction, 0.1);
  EXPECT_EQ(c.numerics.coupling_tolerance, 1e-8);
  EXPECT_EQ(c.numerics.max_coupling_iterations, 30);
  EXPECT_EQ(c.numerics.max_step_cuts, 6);
}

TEST(CaseFileFluid, DefaultsWithoutAndWithAFluidSection) {
  const CaseConfig none = load_case_text("title: defaults\n", "empty.yaml");
  EXPECT_FALSE(none.fluid.has_value());
  EXPECT_TRUE(none.injections.empty());
  EXPECT_TRUE(none.probes.empty());
  const NumericsConfig n;
  EXPECT_EQ(n.min_width_main_m, 0.5e-6);
  EXPECT_EQ(n.min_width_tip_m, 0.1e-6);
  EXPECT_EQ(n.max_closing_fraction, 0.05);
  EXPECT_EQ(n.coupling_tolerance, 1e-9);
  EXPECT_EQ(n.max_coupling_iterations, 60);
  EXPECT_EQ(n.max_step_cuts, 4);
  EXPECT_EQ(none.numerics.min_width_main_m, n.min_width_main_m);
  EXPECT_EQ(none.numerics.min_width_tip_m, n.min_width_tip_m);
  EXPECT_EQ(none.numerics.max_closing_fraction, n.max_closing_fraction);
  EXPECT_EQ(none.numerics.coupling_tolerance, n.coupling_tolerance);
  EXPECT_EQ(none.numerics.max_coupling_iterations, n.max_coupling_iterations);
  EXPECT_EQ(none.numerics.max_step_cuts, n.max_step_cuts);

  const CaseConfig c = load_case_text(fluid_case(), "fluid.yaml");
  ASSERT_TRUE(c.fluid.has_value());  // `fluid: {}` switches the flow network on
  EXPECT_EQ(c.fluid->density_kg_m3, 1000);
  EXPECT_EQ(c.fluid->bulk_modulus_Pa, 2.2e9);
  EXPECT_EQ(c.fluid->viscosity_Pa_s, 1e-3);
  EXPECT_EQ(c.fluid->reference_pressure_Pa, 0);
  EXPECT_EQ(c.fluid->leak_off_coefficient_m_sqrt_s, 0);
  ASSERT_EQ(c.injections.size(), 1u);
  EXPECT_EQ(c.injections[0].name, "injection");
  EXPECT_EQ(c.injections[0].start_time_s, 0);
  EXPECT_EQ(c.injections[0].line, 5);
  ASSERT_EQ(c.fractures.size(), 1u);
  EXPECT_EQ(c.fractures[0].initial_width_m, 0);
  EXPECT_FALSE(c.fractures[0].pressure_Pa.has_value());

  // A fluid section with only an injection (no fluid-filled fracture) is enough.
  const CaseConfig injected_only = load_case_text(
      "fluid: {viscosity: 0.01}\ninjections: [{at: [0, 0], mass_rate: 2}]\n", "inj.yaml");
  ASSERT_TRUE(injected_only.fluid.has_value());
  EXPECT_EQ(injected_only.fluid->viscosity_Pa_s, 0.01);
  EXPECT_EQ(injected_only.fluid->density_kg_m3, 1000);
}

TEST(CaseFileFluid, ExtendsMergesFluidKeyByKeyAndReplacesLists) {
  const CaseConfig c = load_case_file(kCases + "fluid_child.yaml");
  EXPECT_EQ(c.title, "fluid child");
  ASSERT_TRUE(c.fluid.has_value());
  EXPECT_EQ(c.fluid->viscosity_Pa_s, 0.1);                   // overridden
  EXPECT_EQ(c.fluid->density_kg_m3, 1020);                   // kept from the base
  EXPECT_EQ(c.fluid->bulk_modulus_Pa, 2.5e9);                // kept
  EXPECT_EQ(c.fluid->leak_off_coefficient_m_sqrt_s, 1e-5);   // kept
  EXPECT_EQ(c.fluid->reference_pressure_Pa, 0);              // default, never written
  ASSERT_EQ(c.injections.size(), 1u);                        // list replaced as a whole
  EXPECT_EQ(c.injections[0].name, "c");
  EXPECT_EQ(c.injections[0].mass_rate_kg_s, 3);
  EXPECT_EQ(c.injections[0].line, 6);                        // line in the child file
  ASSERT_EQ(c.probes.size(), 1u);                            // list not in child: kept
  EXPECT_EQ(c.probes[0].name, "p1");
  EXPECT_EQ(c.probes[0].line, 10);                           // line in the base file
  ASSERT_EQ(c.fractures.size(), 1u);
  EXPECT_TRUE(c.fractures[0].fluid_filled);
}

TEST(CaseFileFluid, ExtendsNullRemovesTheInheritedFluid) {
  // Removing the fluid leaves the base's injections without one: the error points at
  // the base file, where `injections` was written.
  const std::string label = kCases + "fluid_virtual.yaml";
  expect_error(error_of_text("extends: fluid_base.yaml\nfluid: null\n", label),
               kCases + "fluid_base.yaml", 6, "injections", "'fluid: null' removed it");
  // With everything fluid removed too, the case is valid and has no fluid.
  const CaseConfig c = load_case_text(
      "extends: fluid_base.yaml\nfluid:\ninjections: []\nprobes: []\n"
      "fractures: [{from: [-1, 0], to: [1, 0], initially_open: true}]\n",
      label);
  EXPECT_FALSE(c.fluid.has_value());
  EXPECT_TRUE(c.injections.empty());
}

TEST(CaseFileFluid, FluidFilledNeedsInitiallyOpen) {
  expect_text_error(
      "fractures:\n  - from: [0, 0]\n    to: [1, 0]\n    fluid_filled: true\n", 4,
      "fractures[0].fluid_filled", "needs initially_open: true");
  expect_text_error(
      "fractures:\n  - {from: [0, 0], to: [1, 0], initially_open: false, fluid_filled: true}\n",
      2, "fractures[0].fluid_filled", "needs initially_open: true");
}

TEST(CaseFileFluid, FluidFilledExcludesPrescribedPressure) {
  expect_text_error(
      "fractures:\n  - from: [0, 0]\n    to: [1, 0]\n    initially_open: true\n"
      "    fluid_filled: true\n    pressure: 1e6\n",
      6, "fractures[0].pressure", "fluid_filled");
}

TEST(CaseFileFluid, InitialWidthNeedsFluidFilled) {
  expect_text_error(
      "fractures:\n  - from: [0, 0]\n    to: [1, 0]\n    initially_open: true\n"
      "    initial_width: 1e-6\n",
      5, "fractures[0].initial_width", "only used with fluid_filled: true (got 1e-6)");
  // initial_width 0 (the default) is allowed on any fracture.
  EXPECT_NO_THROW(load_case_text("fractures: [{from: [0, 0], to: [1, 0], initial_width: 0}]\n",
                                 "ok.yaml"));
}

TEST(CaseFileFluid, InitialPressureNeedsFluidFilled) {
  expect_text_error(
      "fractures:\n  - from: [0, 0]\n    to: [1, 0]\n    initially_open: true\n"
      "    initial_pressure: 1.38e6\n",
      5, "fractures[0].initial_pressure", "only used with fluid_filled: true (got 1380000)");
  expect_text_error(
      "fractures:\n  - from: [0, 0]\n    to: [1, 0]\n    initially_open: true\n"
      "    fluid_filled: true\n    initial_pressure: -1\n",
      6, "fractures[0].initial_pressure", "in [0, 1e10]");
  const CaseConfig c = load_case_text(
      "fractures: [{from: [-1, 0], to: [1, 0], initially_open: true, fluid_filled: true,\n"
      "             initial_width: 1.0e-3, initial_pressure: 1.38e6}]\n"
      "fluid: {}\ninjections: [{at: [0, 0], mass_rate: 1}]\n",
      "ok.yaml");
  EXPECT_EQ(c.fractures[0].initial_pressure_Pa, 1.38e6);
  EXPECT_EQ(load_case_text(fluid_case(""), "default.yaml").fractures[0].initial_pressure_Pa, 0.0);
}

TEST(CaseFileFluid, ElasticInitialOpeningNeedsAFluidAtPressureAndNoWidth) {
  expect_text_error(
      "fractures:\n  - from: [0, 0]\n    to: [1, 0]\n    initially_open: true\n"
      "    initial_opening: elastic\n",
      5, "fractures[0].initial_opening", "elastic is only used with fluid_filled: true");
  expect_text_error(
      "fractures:\n  - from: [0, 0]\n    to: [1, 0]\n    initially_open: true\n    fluid_filled: true\n"
      "    initial_opening: elastic\n",
      6, "fractures[0].initial_opening", "elastic needs initial_pressure > 0");
  expect_text_error(
      "fractures:\n  - from: [0, 0]\n    to: [1, 0]\n    initially_open: true\n    fluid_filled: true\n"
      "    initial_opening: elastic\n    initial_pressure: 1e6\n    initial_width: 1e-4\n",
      8, "fractures[0].initial_width", "cannot be given with initial_opening: elastic");
  expect_text_error(
      "fractures:\n  - from: [0, 0]\n    to: [1, 0]\n    initially_open: true\n    fluid_filled: true\n"
      "    initial_opening: wide\n",
      6, "fractures[0].initial_opening", "must be one of: width, elastic");
  const CaseConfig c = load_case_text(
      "fractures: [{from: [-1, 0], to: [1, 0], initially_open: true, fluid_filled: true,\n"
      "             initial_opening: elastic, initial_pressure: 1.0e6}]\n"
      "fluid: {}\ninjections: [{at: [0, 0], mass_rate: 1}]\n",
      "ok.yaml");
  EXPECT_EQ(c.fractures[0].initial_opening, InitialOpening::elastic);
  EXPECT_EQ(load_case_text(fluid_case(""), "default.yaml").fractures[0].initial_opening, InitialOpening::width);
}

TEST(CaseFileFluid, FlowNetworkPartsNeedAFluidSection) {
  expect_text_error("title: x\ninjections:\n  - {at: [0, 0], mass_rate: 1}\n", 2, "injections",
                    "needs a 'fluid' section");
  expect_text_error("title: x\nprobes:\n  - {name: a, at: [0, 0]}\n", 2, "probes",
                    "needs a 'fluid' section");
  expect_text_error(
      "fractures:\n  - {from: [0, 0], to: [1, 0]}\n  - from: [0, 1]\n    to: [1, 1]\n"
      "    initially_open: true\n    fluid_filled: true\n",
      6, "fractures[1].fluid_filled", "needs a 'fluid' section");
}

TEST(CaseFileFluid, FluidSectionNeedsASourceOrAFilledFracture) {
  expect_text_error("title: x\nfluid:\n  viscosity: 0.01\n", 2, "fluid",
                    "at least one item in 'injections' or one fracture with fluid_filled");
  // Probes and a prescribed-pressure fracture are not sources.
  expect_text_error(
      "fluid: {}\nprobes: [{name: a, at: [0, 0]}]\n"
      "fractures: [{from: [0, 0], to: [1, 0], initially_open: true, pressure: 1e6}]\n",
      1, "fluid", "at least one item");
}

TEST(CaseFileFluid, MinWidthAtTheTipNotAboveTheMainWidth) {
  expect_text_error(fluid_case("numerics:\n  min_width_tip: 1e-6\n"), 7,
                    "numerics.min_width_tip",
                    "must be <= numerics.min_width_main (got min_width_tip 1e-6, "
                    "min_width_main 5e-7)");
  expect_text_error(fluid_case("numerics: {min_width_main: 2e-6, min_width_tip: 3e-6}\n"), 6,
                    "numerics.min_width_tip", "must be <= numerics.min_width_main");
  // Only the main width written, below the default tip width: the written key is at fault.
  expect_text_error(fluid_case("numerics:\n  min_width_main: 5e-8\n"), 7,
                    "numerics.min_width_main", "min_width_tip was not set");
  EXPECT_NO_THROW(load_case_text(fluid_case("numerics: {min_width_main: 1e-7}\n"), "eq.yaml"));
}

TEST(CaseFileFluid, ProbeNames) {
  expect_text_error(fluid_case("probes:\n  - {name: \"inlet gauge\", at: [0, 0]}\n"), 7,
                    "probes[0].name",
                    "may contain only letters, digits and '_' (got 'inlet gauge')");
  expect_text_error(fluid_case("probes:\n  - {name: p-1, at: [0, 0]}\n"), 7, "probes[0].name",
                    "letters, digits");
  expect_text_error(fluid_case("probes:\n  - {name: \"\", at: [0, 0]}\n"), 7, "probes[0].name",
                    "must not be empty");
  expect_text_error(fluid_case("probes:\n  - {at: [0, 0]}\n"), 7, "probes[0].name",
                    "is required");
  expect_text_error(fluid_case("probes:\n  - {name: a}\n"), 7, "probes[0].at", "is required");
  expect_text_error(fluid_case("probes:\n  - {name: inlet, at: [0, 0]}\n  - name: tip\n"
                               "    at: [1, 0]\n  - name: inlet\n    at: [2, 0]\n"),
                    10, "probes[2].name", "duplicate probe name 'inlet' (also probes[0])");
}

TEST(CaseFileFluid, InjectionItems) {
  expect_text_error(fluid_case("injections: []\n"), 6, "injections", "duplicate key");
  expect_text_error("fluid: {}\ninjections:\n  - {at: [0, 0]}\n", 3, "injections[0].mass_rate",
                    "is required");
  expect_text_error("fluid: {}\ninjections:\n  - {mass_rate: 1}\n", 3, "injections[0].at",
                    "is required");
  expect_text_error("fluid: {}\ninjections:\n  - {at: [0, 0], mass_rate: 0}\n", 3,
                    "injections[0].mass_rate", "must be in (0, 1e6] (got 0)");
  expect_text_error("fluid: {}\ninjections:\n  - {at: [0, 0], mass_rate: 1, start_time: -1}\n",
                    3, "injections[0].start_time", "must be in [0, 1e10] (got -1)");
  expect_text_error("fluid: {}\ninjections:\n  - {at: [0, 0], mass_rate: 1, rate: 1}\n", 3,
                    "injections[0].rate", "unknown key; allowed keys: name, at, mass_rate, "
                                          "start_time");
  expect_text_error("fluid: {}\ninjections:\n  - {at: [0, 0], mass_rate: 1}\n"
                    "  - {at: [0, 60], mass_rate: 1}\n",
                    4, "injections[1].at", "lies outside the domain");
  expect_text_error(fluid_case("probes:\n  - {name: far, at: [-51, 0]}\n"), 7, "probes[0].at",
                    "lies outside the domain");
}

TEST(CaseFileFluid, FluidAndNumericsRanges) {
  expect_text_error("fluid:\n  density: 0\n", 2, "fluid.density", "must be in [0.01, 1e5] (got 0)");
  expect_text_error("fluid:\n  bulk_modulus: -1\n", 2, "fluid.bulk_modulus", "in [1e5, 1e13]");
  expect_text_error("fluid:\n  viscosity: 0\n", 2, "fluid.viscosity", "in [1e-6, 1e6]");
  expect_text_error("fluid:\n  leak_off_coefficient: -2e-5\n", 2, "fluid.leak_off_coefficient",
                    "must be in [0, 1] (got -2e-5)");
  expect_text_error("fluid:\n  reference_pressure: abc\n", 2, "fluid.reference_pressure",
                    "expected a finite number");
  expect_text_error("fluid:\n  colour: red\n", 2, "fluid.colour",
                    "allowed keys: density, bulk_modulus, viscosity, reference_pressure, "
                    "leak_off_coefficient");
  expect_text_error("fluid: water\n", 1, "fluid", "expected a map");
  expect_text_error("fractures:\n  - {from: [0, 0], to: [1, 0], initial_width: -1}\n", 2,
                    "fractures[0].initial_width", ">= 0");
  expect_text_error("fractures:\n  - {from: [0, 0], to: [1, 0], fluid_filled: yes}\n", 2,
                    "fractures[0].fluid_filled", "expected a boolean");
  expect_text_error("numerics:\n  min_width_main: 0\n", 2, "numerics.min_width_main",
                    "must be in (0, 1] (got 0)");
  expect_text_error("numerics:\n  min_width_tip: -1e-7\n", 2, "numerics.min_width_tip", "in (0, 1]");
  expect_text_error("numerics:\n  max_closing_fraction: 0\n", 2,
                    "numerics.max_closing_fraction", "must be in (0, 1) (got 0)");
  expect_text_error("numerics:\n  max_closing_fraction: 1\n", 2,
                    "numerics.max_closing_fraction", "must be in (0, 1) (got 1)");
  expect_text_error("numerics:\n  coupling_tolerance: 0\n", 2, "numerics.coupling_tolerance",
                    "in (0, 1]");
  expect_text_error("numerics:\n  max_coupling_iterations: 0\n", 2,
                    "numerics.max_coupling_iterations", "in [1, 1e6]");
  expect_text_error("numerics:\n  max_coupling_iterations: 1.5\n", 2,
                    "numerics.max_coupling_iterations", "expected an integer");
  expect_text_error("numerics:\n  max_step_cuts: -1\n", 2, "numerics.max_step_cuts", "in [0, 30]");
  EXPECT_NO_THROW(load_case_text("numerics: {max_step_cuts: 0}\n", "cuts.yaml"));
}

TEST(CaseFileFluid, ErrorInAnExtendedFileNamesThatFile) {
  // The child's fluid override is bad: the error names the child, not the base.
  const std::string label = kCases + "fluid_virtual.yaml";
  expect_error(error_of_text("extends: fluid_base.yaml\nfluid:\n  viscosity: -1\n", label),
               label, 3, "fluid.viscosity", "in [1e-6, 1e6]");
}

}  // namespace
}  // namespace hfdda::io
