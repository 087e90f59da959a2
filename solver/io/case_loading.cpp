// Loading a case file: YAML parsing, the `extends` chain, the checks on the merged
// case, and the public entry points of case_config.hpp.
//
// A file's `extends` base is read first, into the same CaseConfig, so the keys of the
// file then override it one by one (case_fields.hpp: maps merge, lists are replaced).

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "io/breakable_patterns.hpp"
#include "io/case_checks.hpp"
#include "io/case_config.hpp"
#include "io/case_schema.hpp"
#include "io/case_tables.hpp"
#include "io/case_text.hpp"
#include "io/fracture_maps.hpp"

namespace hfdda::io {

using namespace schema;

namespace {

std::optional<std::string> read_text_file(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) return std::nullopt;
  return text.str();
}

YAML::Node parse_yaml(const std::string& text, const std::string& file) {
  try {
    return YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw InputError(file, e.mark.is_null() ? 0 : e.mark.line + 1, "(syntax)",
                     "YAML syntax error: " + e.msg);
  }
}

/// A file of the extends chain: its label (for messages) and identity (for cycles).
struct ChainEntry {
  std::string id;
  std::string label;
};

std::string file_identity(const std::string& path) {
  std::error_code ec;
  const auto canonical = std::filesystem::weakly_canonical(path, ec);
  return ec ? path : canonical.string();
}

std::string resolve_relative(const std::string& from_file, const std::string& target) {
  const std::filesystem::path path(target);
  if (path.is_absolute()) return path.lexically_normal().string();
  return (std::filesystem::path(from_file).parent_path() / path).lexically_normal().string();
}

void apply_case_text(const std::string& text, const std::string& file,
                     std::vector<ChainEntry>& chain, CaseConfig& config, Provenance& where);

/// Reads the base file named by `extends` into `config` before this file's keys.
void apply_base(FileReader& r, const YAML::Node& node, std::vector<ChainEntry>& chain,
                CaseConfig& config, Provenance& where) {
  const std::string target = read_string(r, node, "extends");
  if (target.empty()) r.fail(node, "extends", "must name a case file (got an empty string)");
  const std::string base = resolve_relative(r.file(), target);
  const std::string id = file_identity(base);
  for (const auto& entry : chain) {
    if (entry.id != id) continue;
    std::vector<std::string> labels;
    for (const auto& e : chain) labels.push_back(clip(e.label));
    labels.push_back(clip(base));
    r.fail(node, "extends", "extends cycle: " + join(labels, " -> "));
  }
  const auto base_text = read_text_file(base);
  if (!base_text) r.fail(node, "extends", "file '" + clip(base) + "' cannot be read");
  chain.push_back({id, base});
  apply_case_text(*base_text, base, chain, config, where);
  chain.pop_back();
}

void apply_case_text(const std::string& text, const std::string& file,
                     std::vector<ChainEntry>& chain, CaseConfig& config, Provenance& where) {
  config.source_text += file + "\n" + text + "\n";
  const YAML::Node root = parse_yaml(prepare_case_text(text, file), file);
  check_yaml_tree(root, file);
  if (root.IsNull())
    throw InputError(file, 0, "(document)",
                     "empty case file: it sets no key (a case file that keeps every default "
                     "still says so, e.g. with a title)");
  FileReader reader(file, where);
  if (root.IsMap()) {
    for (const auto& entry : root) {
      if (!entry.first.IsScalar() || entry.first.Scalar() != "extends") continue;
      reader.set_null_line(reader.line(entry.first));
      apply_base(reader, entry.second, chain, config, where);
      break;  // a second extends is reported as a duplicate key below
    }
  }
  parse_map(reader, root, "", case_table(), config);
}

/// Where the `mesh` section was last written (the top file, line 0, when it never was),
/// so errors found when the mesh is built can point at it.
void record_mesh_origin(const Provenance& where, CaseConfig& config) {
  const auto it = where.find("mesh");
  config.mesh_file = it != where.end() ? it->second.file : config.file;
  config.mesh.line = it != where.end() ? it->second.line : 0;
}

}  // namespace

CaseConfig load_case_text(const std::string& yaml_text, const std::string& file_label) {
  CaseConfig config;
  Provenance where;
  std::vector<ChainEntry> chain{{file_identity(file_label), file_label}};
  apply_case_text(yaml_text, file_label, chain, config, where);
  const MergedChecker checker(where, file_label);
  for (const auto& check : cross_checks()) check.check(config, checker);
  append_breakable_pattern_lines(config);
  config.file = file_label;
  append_fracture_map_lines(config);
  record_mesh_origin(where, config);
  return config;
}

CaseConfig load_case_file(const std::string& path) {
  const auto text = read_text_file(path);
  if (!text) throw InputError(path, 0, "(file)", "cannot be read");
  return load_case_text(*text, path);
}

}  // namespace hfdda::io
