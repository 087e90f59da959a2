// hfdda_fuzz_cases: deterministic mutation fuzzing of the case-file reader.
//
//   hfdda_fuzz_cases [--seconds S] [--max-inputs N] [--seed K | --default-seed K] [--corpus DIR]...
//                    [--save-failures DIR] [--input I] [--input-timeout S] [--max-model-blocks B]
//   hfdda_fuzz_cases FILE...        run saved inputs (a finding, a regression) once each
//
// Runs every seed of the corpus as it is, then mutated inputs 0, 1, 2, ... until the
// time or the input count is reached. Input I depends only on the seed K and the corpus,
// so `--seed K --input I` makes it again. Exit 0: no finding; 1: a finding (saved to the
// --save-failures directory); 2: bad usage; 3: a hang; a crash ends the process after
// saving the input. The seed: --seed, else $HFDDA_FUZZ_SEED, else --default-seed (what
// CTest passes), else 20250101.

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "case_mutator.hpp"
#include "case_reader_target.hpp"
#include "crash_guard.hpp"

namespace fs = std::filesystem;
using namespace hfdda::fuzz;

namespace {

constexpr std::uint64_t kDefaultSeed = 20250101;
constexpr int kMaxFindings = 10;  ///< a run stops after this many: they are often one bug

struct Options {
  double seconds = 10.0;
  std::uint64_t max_inputs = 0;  ///< 0: no limit but the time
  std::uint64_t seed = kDefaultSeed;
  std::vector<std::string> corpus_dirs;
  std::string save_dir = ".";
  std::optional<std::uint64_t> only_input;
  double input_timeout_s = 20.0;
  TargetOptions target;
  std::vector<std::string> files;
};

const char* const kUsage =
    "usage: hfdda_fuzz_cases [--seconds S] [--max-inputs N] [--seed K | --default-seed K] [--corpus DIR]...\n"
    "                        [--save-failures DIR] [--input I] [--input-timeout S] [--max-model-blocks B]\n"
    "       hfdda_fuzz_cases FILE...   run saved inputs once each\n"
    "Mutates the case files of the corpus directories (*.yaml) and runs each input through\n"
    "the case reader (and, for meshes of at most B blocks, the model builder). Defaults:\n"
    "10 s; the seed is --seed, else $HFDDA_FUZZ_SEED, else --default-seed, else 20250101;\n"
    "findings are saved to the current directory; an input running longer than 20 s is a\n"
    "hang; B = 2000. --input I writes input I of the seed to a file and runs it.\n";

int usage_error(const std::string& message) {
  std::fprintf(stderr, "hfdda_fuzz_cases: %s\n%s", message.c_str(), kUsage);
  return 2;
}

std::optional<double> to_number(const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !(v >= 0)) return std::nullopt;
  return v;
}

std::optional<std::uint64_t> to_count(const std::string& text) {
  if (text.empty() || text.size() > 19 || text.find_first_not_of("0123456789") != std::string::npos)
    return std::nullopt;
  return std::stoull(text);
}

/// Parses the command line; returns an exit code when the program should stop.
std::optional<int> parse(int argc, char** argv, Options& o) {
  std::optional<std::uint64_t> seed;  // --seed or $HFDDA_FUZZ_SEED: over --default-seed
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    if (arg == "-h" || arg == "--help") {
      std::fputs(kUsage, stdout);
      return 0;
    }
    if (arg.starts_with("--") && !has_value) return usage_error(arg + " needs a value");
    if (arg == "--seconds") {
      const auto v = to_number(argv[++i]);
      if (!v) return usage_error("--seconds needs a number >= 0");
      o.seconds = *v;
    } else if (arg == "--max-inputs" || arg == "--seed" || arg == "--default-seed" || arg == "--input") {
      const auto v = to_count(argv[++i]);
      if (!v) return usage_error(arg + " needs a whole number");
      if (arg == "--max-inputs") o.max_inputs = *v;
      else if (arg == "--seed") seed = *v;
      else if (arg == "--default-seed") o.seed = *v;
      else o.only_input = *v;
    } else if (arg == "--input-timeout" || arg == "--max-model-blocks") {
      const auto v = to_number(argv[++i]);
      if (!v) return usage_error(arg + " needs a number >= 0");
      if (arg == "--input-timeout") o.input_timeout_s = std::max(0.1, *v);
      else o.target.max_model_blocks = *v;
    } else if (arg == "--corpus") {
      o.corpus_dirs.push_back(argv[++i]);
    } else if (arg == "--save-failures") {
      o.save_dir = argv[++i];
    } else if (arg.starts_with("-")) {
      return usage_error("unknown option '" + arg + "'");
    } else {
      o.files.push_back(arg);
    }
  }
  if (const char* env = std::getenv("HFDDA_FUZZ_SEED"); env && !seed) {
    seed = to_count(env);
    if (!seed) return usage_error("HFDDA_FUZZ_SEED must be a whole number (got '" + std::string(env) + "')");
  }
  if (seed) o.seed = *seed;
  if (o.files.empty() && o.corpus_dirs.empty()) return usage_error("no --corpus directory and no input file given");
  return std::nullopt;
}

std::optional<std::string> read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void write_file(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

/// Counts of what the inputs did, to show the run explored more than the first check.
struct Tally {
  std::uint64_t inputs = 0, bytes = 0, findings = 0;
  std::uint64_t accepted = 0, models = 0, known = 0, refused_read = 0, refused_model = 0;
  std::size_t longest_rule = 0;  ///< characters; the contract bounds the whole message
  std::map<std::string, std::uint64_t> keys;   ///< "stage key" of refusals, list indices left out
  std::map<std::string, std::uint64_t> rules;  ///< the start of the rules of refusals
  std::map<std::string, std::uint64_t> lines;  ///< line ranges of read refusals
  std::map<std::string, std::uint64_t> mutations;

  void add(const TargetResult& r, std::size_t size) {
    ++inputs;
    bytes += size;
    if (r.outcome == Outcome::accepted) {
      ++accepted;
      if (r.model_built) ++models;
      if (!r.known_problem.empty()) ++known;
    } else if (r.outcome == Outcome::refused) {
      (r.stage == "model" ? refused_model : refused_read)++;
      ++keys[r.stage + "  " + without_indices(r.key)];
      ++rules[rule_kind(r.rule)];
      longest_rule = std::max(longest_rule, r.rule.size());
      if (r.stage == "read")
        ++lines[r.line == 0   ? "0 (whole file)"
                : r.line == 1 ? "1"
                : r.line <= 5 ? "2-5"
                : r.line <= 20 ? "6-20"
                               : "> 20"];
    } else {
      ++findings;
    }
  }

  void print(double seconds) const {
    std::printf("inputs: %llu in %.1f s (%.0f/s), mean size %.0f bytes\n", as_ull(inputs), seconds,
                seconds > 0 ? static_cast<double>(inputs) / seconds : 0.0,
                inputs ? static_cast<double>(bytes) / static_cast<double>(inputs) : 0.0);
    std::printf("accepted: %llu (model built for %llu, not built for %llu with a known problem); refused by the "
                "reader: %llu; by the model builder: %llu; findings: %llu\n",
                as_ull(accepted), as_ull(models), as_ull(known), as_ull(refused_read), as_ull(refused_model),
                as_ull(findings));
    std::printf("longest rule: %zu characters\n", longest_rule);
    std::printf("refusals by line:");
    for (const auto& [range, n] : lines) std::printf("  %s: %llu", range.c_str(), as_ull(n));
    std::printf("\n");
    print_top("refusals by stage and key", keys, 25);
    print_top("refusals by rule (its first words)", rules, 15);
    std::printf("mutations applied:");
    for (const auto& [name, n] : mutations) std::printf("  %s %llu", name.c_str(), as_ull(n));
    std::printf("\n");
  }

  static unsigned long long as_ull(std::uint64_t n) { return static_cast<unsigned long long>(n); }

  static void print_top(const char* title, const std::map<std::string, std::uint64_t>& counts, std::size_t shown) {
    std::vector<std::pair<std::uint64_t, std::string>> sorted;
    for (const auto& [text, n] : counts) sorted.emplace_back(n, text);
    std::stable_sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    std::printf("%s (%zu distinct), most frequent first:\n", title, sorted.size());
    for (std::size_t i = 0; i < sorted.size() && i < shown; ++i)
      std::printf("  %8llu  %s\n", as_ull(sorted[i].first), sorted[i].second.c_str());
    if (sorted.size() > shown) std::printf("  ... and %zu more\n", sorted.size() - shown);
  }

  /// "fractures[3].from" -> "fractures[].from": the keys of one list count together.
  static std::string without_indices(const std::string& key) {
    std::string out;
    bool in_index = false;
    for (const char c : key) {
      if (c == '[') in_index = true, out += c;
      else if (c == ']') in_index = false, out += c;
      else if (!in_index) out += c;
    }
    return out;
  }

  /// The rule up to the first value it echoes: "must be in [0, 1e10] (got 1e200)" ->
  /// "must be in [0, 1e10]", "unclosed quote: the string ..." -> "unclosed quote".
  static std::string rule_kind(const std::string& rule) {
    const std::size_t cut = std::min({rule.find(" (got"), rule.find(':'), rule.find('\''), std::size_t{70}});
    return rule.substr(0, cut);
  }
};

/// Runs one input under the guard; a finding is saved and reported.
TargetResult run_one(CrashGuard& guard, const Options& o, const std::string& input, const std::string& name,
                     const fs::path& save_path) {
  guard.enter(input, save_path.string(), name);
  const TargetResult r = run_case_reader(input, o.target);
  guard.leave();
  if (r.outcome == Outcome::finding) {
    write_file(save_path, input);
    std::printf("FINDING on %s: %s\n  input saved to %s\n  reproduce with: hfdda_fuzz_cases %s\n", name.c_str(),
                describe(r).c_str(), save_path.c_str(), save_path.c_str());
    std::fflush(stdout);
  }
  return r;
}

int replay_files(const Options& o) {
  CrashGuard guard(o.input_timeout_s);
  int findings = 0;
  for (const auto& file : o.files) {
    const auto text = read_file(file);
    if (!text) return usage_error("cannot read '" + file + "'");
    const auto start = std::chrono::steady_clock::now();
    guard.enter(*text, "", file);
    const TargetResult r = run_case_reader(*text, o.target);
    guard.leave();
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    std::printf("%s: %s (%.1f ms)\n", file.c_str(), describe(r).c_str(), ms);
    if (r.outcome == Outcome::finding) ++findings;
  }
  return findings > 0 ? 1 : 0;
}

std::vector<std::pair<std::string, std::string>> load_corpus(const std::vector<std::string>& dirs) {
  std::vector<std::pair<std::string, std::string>> seeds;  // (file name, text)
  for (const auto& dir : dirs) {
    std::vector<fs::path> paths;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(dir, ec))
      if (entry.is_regular_file() && entry.path().extension() == ".yaml") paths.push_back(entry.path());
    std::sort(paths.begin(), paths.end());  // the order makes input I the same everywhere
    for (const auto& p : paths)
      if (auto text = read_file(p)) seeds.emplace_back(p.filename().string(), std::move(*text));
  }
  return seeds;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  if (const auto code = parse(argc, argv, o)) return *code;
  if (!o.files.empty()) return replay_files(o);

  const auto corpus = load_corpus(o.corpus_dirs);
  if (corpus.empty()) return usage_error("no *.yaml file in the corpus directories");
  std::error_code ec;
  fs::create_directories(o.save_dir, ec);
  if (!fs::is_directory(o.save_dir)) return usage_error("cannot create the directory '" + o.save_dir + "'");
  std::vector<std::string> texts;
  for (const auto& [name, text] : corpus) texts.push_back(text);
  const CaseMutator mutator(texts);
  const std::string seed_text = std::to_string(o.seed);
  auto input_name = [&](std::uint64_t i) { return "input " + std::to_string(i) + " of seed " + seed_text; };
  auto input_path = [&](std::uint64_t i) {
    return fs::path(o.save_dir) / ("finding-" + seed_text + "-" + std::to_string(i) + ".yaml");
  };

  CrashGuard guard(o.input_timeout_s);
  if (o.only_input) {
    Rng rng = input_rng(o.seed, *o.only_input);
    std::vector<std::string> applied;
    const std::string input = mutator.make_input(rng, &applied);
    const fs::path path = fs::path(o.save_dir) / ("input-" + seed_text + "-" + std::to_string(*o.only_input) + ".yaml");
    write_file(path, input);
    std::printf("%s written to %s (mutations:", input_name(*o.only_input).c_str(), path.c_str());
    for (const auto& a : applied) std::printf(" %s", a.c_str());
    std::printf(")\n");
    const TargetResult r = run_one(guard, o, input, input_name(*o.only_input), input_path(*o.only_input));
    std::printf("%s\n", describe(r).c_str());
    return r.outcome == Outcome::finding ? 1 : 0;
  }

  std::printf("hfdda_fuzz_cases: seed %s, %zu corpus files, %.0f s", seed_text.c_str(), corpus.size(), o.seconds);
  if (o.max_inputs > 0) std::printf(" or %llu inputs", static_cast<unsigned long long>(o.max_inputs));
  std::printf(", models up to %.0f blocks\n", o.target.max_model_blocks);
  std::fflush(stdout);

  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  Tally seeds_tally, tally;
  for (const auto& [name, text] : corpus) {
    const TargetResult r = run_one(guard, o, text, "corpus file " + name, fs::path(o.save_dir) / ("finding-" + name));
    seeds_tally.add(r, text.size());
    if (r.outcome != Outcome::accepted) std::printf("  corpus file %s: %s\n", name.c_str(), describe(r).c_str());
  }
  std::printf("corpus as is: %llu accepted (model built for %llu), %llu refused, %llu findings\n",
              Tally::as_ull(seeds_tally.accepted), Tally::as_ull(seeds_tally.models),
              Tally::as_ull(seeds_tally.refused_read + seeds_tally.refused_model), Tally::as_ull(seeds_tally.findings));

  const auto mutation_start = elapsed();
  for (std::uint64_t i = 0; o.max_inputs == 0 || i < o.max_inputs; ++i) {
    if (elapsed() >= o.seconds) break;
    Rng rng = input_rng(o.seed, i);
    std::vector<std::string> applied;
    const std::string input = mutator.make_input(rng, &applied);
    for (const auto& a : applied) ++tally.mutations[a];
    const TargetResult r = run_one(guard, o, input, input_name(i), input_path(i));
    tally.add(r, input.size());
    if (tally.findings >= kMaxFindings) {
      std::printf("stopping after %d findings\n", kMaxFindings);
      break;
    }
  }
  tally.print(elapsed() - mutation_start);
  const std::uint64_t findings = seeds_tally.findings + tally.findings;
  if (findings > 0) {
    std::printf("hfdda_fuzz_cases: %llu findings, saved in %s\n", Tally::as_ull(findings), o.save_dir.c_str());
    return 1;
  }
  std::printf("hfdda_fuzz_cases: no finding\n");
  return 0;
}
