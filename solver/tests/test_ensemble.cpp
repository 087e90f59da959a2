// Ensemble realisations: their seeds depend only on the master seed, the index and which
// groups are resampled; a held group draws the same values in every realisation; the map
// times; records written and read back; resume lists only what has no record.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "ensemble/ensemble_run.hpp"
#include "ensemble/realisation.hpp"
#include "io/case_config.hpp"
#include "simulation/parameter_sampling.hpp"

namespace hfdda {
namespace {

const std::string kTinyCase = std::string(HFDDA_SOURCE_DIR) + "/verification/ensembles/tiny.yaml";

io::EnsembleConfig ensemble_with(std::vector<std::string> resample, int master_seed = 7) {
  io::EnsembleConfig e;
  e.master_seed = master_seed;
  e.resample = std::move(resample);
  return e;
}

TEST(RealisationSeeds, DependOnlyOnMasterSeedIndexAndGroup) {
  const io::EnsembleConfig all = ensemble_with({"network", "rock", "natural_fractures", "fluid"});
  const ensemble::RealisationSeeds a = ensemble::realisation_seeds(all, 3);
  EXPECT_EQ(a.of_group, ensemble::realisation_seeds(all, 3).of_group);  // recomputed: the same
  EXPECT_EQ(a.of_group.size(), ensemble::parameter_groups().size());
  // Other index, other master seed: every group's seed changes.
  const ensemble::RealisationSeeds b = ensemble::realisation_seeds(all, 4);
  const ensemble::RealisationSeeds c = ensemble::realisation_seeds(ensemble_with(all.resample, 8), 3);
  std::set<std::uint64_t> seen;
  for (const std::string& g : ensemble::parameter_groups()) {
    EXPECT_NE(a.of_group.at(g), b.of_group.at(g)) << g;
    EXPECT_NE(a.of_group.at(g), c.of_group.at(g)) << g;
    seen.insert(a.of_group.at(g));
  }
  EXPECT_EQ(seen.size(), ensemble::parameter_groups().size());  // groups have their own streams
}

TEST(RealisationSeeds, HeldGroupsKeepTheirSeedAcrossRealisations) {
  // Seed 5.5: "reservoir held constant, fluid varied".
  const io::EnsembleConfig fluid_only = ensemble_with({"fluid"});
  const ensemble::RealisationSeeds r0 = ensemble::realisation_seeds(fluid_only, 0);
  const ensemble::RealisationSeeds r9 = ensemble::realisation_seeds(fluid_only, 9);
  for (const char* held : {"network", "rock", "natural_fractures"}) EXPECT_EQ(r0.of_group.at(held), r9.of_group.at(held));
  EXPECT_NE(r0.of_group.at("fluid"), r9.of_group.at("fluid"));
  EXPECT_EQ(r0.network_seed(), r9.network_seed());
  EXPECT_GE(r0.network_seed(), 0);
}

TEST(ParameterGroups, EveryDistributedKeyHasItsGroup) {
  EXPECT_EQ(simulation::parameter_group("materials[0].youngs_modulus"), "rock");
  EXPECT_EQ(simulation::parameter_group("joints.tensile_strength"), "rock");
  EXPECT_EQ(simulation::parameter_group("far_field.sxx"), "rock");
  EXPECT_EQ(simulation::parameter_group("fracture_sets[1].hydraulic_width"), "natural_fractures");
  EXPECT_EQ(simulation::parameter_group("fractures[0].friction_angle"), "natural_fractures");
  EXPECT_EQ(simulation::parameter_group("fluid.viscosity"), "fluid");
  EXPECT_EQ(simulation::parameter_group("injections[0].mass_rate"), "fluid");
  EXPECT_THROW(simulation::parameter_group("time.dt"), std::invalid_argument);
}

TEST(ParameterSampler, GroupSeedsHoldOneGroupWhileAnotherVaries) {
  const stochastic::ScalarDistribution law = stochastic::ScalarDistribution::uniform(1.0, 2.0);
  simulation::ParameterSampler a({{"rock", 1}, {"natural_fractures", 2}, {"fluid", 3}});
  simulation::ParameterSampler b({{"rock", 1}, {"natural_fractures", 2}, {"fluid", 4}});
  EXPECT_EQ(a.draw("joints.tensile_strength", law, "joint"), b.draw("joints.tensile_strength", law, "joint"));
  EXPECT_NE(a.draw("fluid.viscosity", law, "run"), b.draw("fluid.viscosity", law, "run"));
}

TEST(MapTimes, EveryMultipleUpToTheEndAndTheEnd) {
  io::EnsembleConfig e;
  e.map_every_s = 900;
  EXPECT_EQ(ensemble::map_times(e, 3600), (std::vector<double>{900, 1800, 2700, 3600}));
  EXPECT_EQ(ensemble::map_times(e, 2000), (std::vector<double>{900, 1800, 2000}));
  EXPECT_EQ(ensemble::map_times(e, 900), (std::vector<double>{900}));
}

TEST(EnsembleRecords, WrittenAtomicallyReadBackAndSkippedOnResume) {
  const io::CaseConfig config = io::load_case_file(kTinyCase);
  const ensemble::EnsembleGeometry geometry = ensemble::ensemble_geometry(config);
  EXPECT_EQ(geometry.map_times_s, (std::vector<double>{120, 240, 300}));
  EXPECT_EQ(geometry.grid.nx * geometry.grid.ny, 36);
  const std::string dir = (std::filesystem::path(testing::TempDir()) / "hfdda_ensemble_records").string();
  std::filesystem::remove_all(dir);
  const ensemble::EnsembleManifest manifest = ensemble::make_manifest(config, geometry, {});
  ensemble::prepare_directory(dir, manifest, geometry);
  EXPECT_EQ(ensemble::pending_realisations(dir, manifest).size(), 8u);

  const std::optional<ensemble::RealisationRecord> r = ensemble::run_realisation(config, geometry, 5);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, "completed") << r->message;
  EXPECT_EQ(r->maps.snapshots.size(), 3u);
  EXPECT_FALSE(r->maps.snapshots.back().open_joints.empty());  // the initial fracture is open
  ensemble::write_record(dir, *r);
  const std::vector<long> pending = ensemble::pending_realisations(dir, manifest);
  EXPECT_EQ(pending.size(), 7u);
  EXPECT_EQ(std::count(pending.begin(), pending.end(), 5L), 0);
  // No temporary file is left behind.
  for (const auto& entry : std::filesystem::directory_iterator(dir + "/realisations"))
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();

  const std::vector<ensemble::RealisationRecord> back = ensemble::read_records(dir);
  ASSERT_EQ(back.size(), 1u);
  EXPECT_EQ(back[0].index, 5);
  EXPECT_EQ(back[0].seeds.of_group, r->seeds.of_group);
  EXPECT_EQ(back[0].mesh, geometry.mesh);
  ASSERT_EQ(back[0].maps.snapshots.size(), r->maps.snapshots.size());
  for (std::size_t t = 0; t < r->maps.snapshots.size(); ++t) {
    EXPECT_EQ(back[0].maps.snapshots[t].open_joints, r->maps.snapshots[t].open_joints);
    EXPECT_EQ(back[0].maps.snapshots[t].wet_cells, r->maps.snapshots[t].wet_cells);
  }
  ASSERT_EQ(back[0].draws.size(), r->draws.size());
  EXPECT_EQ(back[0].draws[0].mean, r->draws[0].mean);  // numbers read back exactly
  // The quality of its steps is taken from its history and read back exactly.
  ASSERT_TRUE(r->quality.known);
  EXPECT_GT(r->quality.max_aperture_m, 0.0);
  EXPECT_GT(r->quality.max_block_strain, 0.0);
  EXPECT_LT(r->quality.max_block_strain, ensemble::kImplausibleStepStrain);
  EXPECT_GT(r->quality.final_injection_pressure_Pa, 0.0);
  EXPECT_TRUE(back[0].quality.known);
  EXPECT_EQ(back[0].quality.max_block_strain, r->quality.max_block_strain);
  EXPECT_EQ(back[0].quality.final_injection_pressure_Pa, r->quality.final_injection_pressure_Pa);
  EXPECT_EQ(back[0].quality.max_cycle_holds, r->quality.max_cycle_holds);

  // The same realisation run again gives the same record (seeds from the index alone).
  const std::optional<ensemble::RealisationRecord> again = ensemble::run_realisation(config, geometry, 5);
  ASSERT_TRUE(again);
  EXPECT_EQ(again->maps.snapshots.back().wet_joints, r->maps.snapshots.back().wet_joints);
  EXPECT_EQ(again->draws[0].mean, r->draws[0].mean);

  // Another ensemble in the same directory is refused, naming what differs.
  ensemble::EnsembleManifest other = manifest;
  other.master_seed += 1;
  try {
    ensemble::prepare_directory(dir, other, geometry);
    FAIL() << "another master seed was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("master_seed"), std::string::npos) << e.what();
  }
  // So is the same ensemble from another build of the solver (its realisations may differ).
  EXPECT_EQ(manifest.solver_build.size(), 16u);
  ensemble::EnsembleManifest rebuilt = manifest;
  rebuilt.solver_build = "0123456789abcdef";
  try {
    ensemble::prepare_directory(dir, rebuilt, geometry);
    FAIL() << "another build was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("another build of the solver"), std::string::npos) << e.what();
  }
}

TEST(EnsembleRecords, EditingABaseFileMakesAnotherEnsemble) {
  // A resumed ensemble must not mix realisations of two versions of a case: the
  // manifest's case hash covers the files the top file extends.
  const std::filesystem::path dir = std::filesystem::path(testing::TempDir()) / "hfdda_ensemble_extends";
  std::filesystem::create_directories(dir);
  std::filesystem::copy_file(kTinyCase, dir / "base.yaml", std::filesystem::copy_options::overwrite_existing);
  { std::ofstream(dir / "top.yaml") << "extends: base.yaml\ntitle: \"tiny, extended\"\n"; }
  auto hash = [&] {
    const io::CaseConfig c = io::load_case_file((dir / "top.yaml").string());
    return ensemble::make_manifest(c, ensemble::ensemble_geometry(c), {}).case_hash;
  };
  const std::string before = hash();
  EXPECT_EQ(hash(), before);
  { std::ofstream(dir / "base.yaml", std::ios::app) << "probes: [{name: inlet, at: [0, 0]}]\n"; }
  EXPECT_NE(hash(), before);
}

TEST(EnsembleRecords, EditingAFractureMapMakesAnotherEnsemble) {
  // The same for the CSV files of `fracture_maps`, read when the case is loaded.
  const std::filesystem::path dir = std::filesystem::path(testing::TempDir()) / "hfdda_ensemble_map";
  std::filesystem::create_directories(dir);
  std::filesystem::copy_file(kTinyCase, dir / "base.yaml", std::filesystem::copy_options::overwrite_existing);
  { std::ofstream(dir / "map.csv") << "x1,y1,x2,y2\n-10,5,10,5\n"; }
  { std::ofstream(dir / "top.yaml") << "extends: base.yaml\nfracture_maps: [{name: mapped, file: map.csv, natural: true}]\n"; }
  auto hash = [&] {
    const io::CaseConfig c = io::load_case_file((dir / "top.yaml").string());
    return ensemble::make_manifest(c, ensemble::ensemble_geometry(c), {}).case_hash;
  };
  const std::string before = hash();
  EXPECT_EQ(hash(), before);
  { std::ofstream(dir / "map.csv") << "x1,y1,x2,y2\n-10,6,10,6\n"; }
  EXPECT_NE(hash(), before);
}

TEST(EnsembleRecords, ACorruptRecordIsAnErrorNamingItsFile) {
  const std::string path = (std::filesystem::path(testing::TempDir()) / "r000001.json").string();
  { std::ofstream(path) << "{\"index\": 1, \"status\": \"completed\""; }
  try {
    ensemble::read_record(path);
    FAIL() << "a truncated record was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

// Each record says where and when it ran; the summary adds up how the processes spent
// the span: the realisations, the waits for an index, and the idle time at the end.
TEST(EnsembleRecords, ScheduleIsKeptAndSummed) {
  const io::CaseConfig config = io::load_case_file(kTinyCase);
  const ensemble::EnsembleGeometry geometry = ensemble::ensemble_geometry(config);
  const std::string dir = (std::filesystem::path(testing::TempDir()) / "hfdda_ensemble_schedule").string();
  std::filesystem::remove_all(dir);
  ensemble::prepare_directory(dir, ensemble::make_manifest(config, geometry, {}), geometry);
  // {index, process, start [s], waited [s], wall [s]}: process 0 ends at 115, process 1 at 121.
  const double runs[3][5] = {{0, 0, 100.0, 0.0, 10.0}, {1, 1, 101.0, 1.0, 20.0}, {2, 0, 110.0, 0.0, 5.0}};
  for (const auto& run : runs) {
    ensemble::RealisationRecord r;
    r.index = static_cast<long>(run[0]);
    r.status = "completed";
    r.seeds = ensemble::realisation_seeds(*config.ensemble, r.index);
    r.maps.index = r.index;
    r.mesh = geometry.mesh;
    r.process = static_cast<int>(run[1]);
    r.started_unix_s = 1.7e9 + run[2];
    r.waited_s = run[3];
    r.wall_s = run[4];
    ensemble::write_record(dir, r);
  }
  const ensemble::RealisationRecord back = ensemble::read_record(dir + "/realisations/r000001.json");
  EXPECT_EQ(back.process, 1);
  EXPECT_EQ(back.started_unix_s, 1.7e9 + 101.0);
  EXPECT_EQ(back.waited_s, 1.0);

  ensemble::write_ensemble_maps(dir, {dir});
  std::ifstream in(dir + "/ensemble_summary.json");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  auto number_after = [&](const std::string& key) {
    const std::size_t at = text.find("\"" + key + "\":");
    EXPECT_NE(at, std::string::npos) << key;
    return at == std::string::npos ? -1.0 : std::stod(text.substr(at + key.size() + 3));
  };
  EXPECT_EQ(number_after("realisations_timed"), 3.0);
  EXPECT_EQ(number_after("processes_seen"), 2.0);
  EXPECT_NEAR(number_after("span_s"), 21.0, 1e-6);
  EXPECT_NEAR(number_after("busy_s"), 35.0, 1e-9);
  EXPECT_NEAR(number_after("waited_for_index_s"), 1.0, 1e-9);
  EXPECT_NEAR(number_after("idle_at_end_s"), 6.0, 1e-6);
}

TEST(EnsembleRecords, CompletedRealisationsWithStrainedBlocksAreCountedAndKept) {
  const io::CaseConfig config = io::load_case_file(kTinyCase);
  const ensemble::EnsembleGeometry geometry = ensemble::ensemble_geometry(config);
  const std::string dir = (std::filesystem::path(testing::TempDir()) / "hfdda_ensemble_quality").string();
  std::filesystem::remove_all(dir);
  ensemble::prepare_directory(dir, ensemble::make_manifest(config, geometry, {}), geometry);
  // {status, quality known, largest step strain}: a plausible run, one strained by 3 %,
  // a failed one (counted as failed only), a record written before quality was kept.
  struct Run {
    const char* status;
    bool known;
    double strain;
  };
  const Run runs[4] = {{"completed", true, 0.002}, {"completed", true, 0.03}, {"failed", true, 0.5},
                       {"completed", false, 0.0}};
  for (long i = 0; i < 4; ++i) {
    ensemble::RealisationRecord r;
    r.index = i;
    r.status = runs[i].status;
    r.seeds = ensemble::realisation_seeds(*config.ensemble, r.index);
    r.maps.index = r.index;
    r.maps.snapshots.push_back({{1}, {1}, {0}, {0}});
    r.mesh = geometry.mesh;
    r.quality.known = runs[i].known;
    r.quality.max_block_strain = runs[i].strain;
    r.quality.max_aperture_m = 0.5;
    r.quality.final_injection_pressure_Pa = 12.0;
    ensemble::write_record(dir, r);
  }
  EXPECT_FALSE(ensemble::read_record(dir + "/realisations/r000003.json").quality.known);
  const ensemble::EnsembleSummary summary = ensemble::write_ensemble_maps(dir, {dir});
  EXPECT_EQ(summary.completed, 3);
  EXPECT_EQ(summary.failed, 1);
  EXPECT_EQ(summary.completed_with_strained_blocks, 1);
  const nlohmann::json s = nlohmann::json::parse(std::ifstream(dir + "/ensemble_summary.json"));
  const nlohmann::json& p = s.at("plausibility");
  EXPECT_EQ(p.at("step_strain_limit"), ensemble::kImplausibleStepStrain);
  EXPECT_EQ(p.at("completed_with_strained_blocks"), 1);
  EXPECT_EQ(p.at("completed_quality_unknown"), 1);
  ASSERT_EQ(p.at("strained").size(), 1u);
  EXPECT_EQ(p.at("strained")[0].at("index"), 1);
  EXPECT_EQ(p.at("strained")[0].at("max_block_strain"), 0.03);
  // They stay in the maps: every record's snapshot counts.
  EXPECT_EQ(s.at("maps")[0].at("realisations"), 4);
}

}  // namespace
}  // namespace hfdda
