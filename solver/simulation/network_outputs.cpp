#include "simulation/network_outputs.hpp"

#include <charconv>
#include <utility>
#include <vector>

#include "io/output.hpp"

namespace hfdda::simulation {

namespace {

/// Shortest text that reads back to v (locale-independent).
void append(std::string& out, double v) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
  out.append(buffer, result.ptr);
}

void append(std::string& out, int v) { out += std::to_string(v); }

}  // namespace

void write_network_outputs(const std::string& dir, const io::CaseConfig& c, const FracturedMesh& fractured) {
  const mesh::Mesh& m = fractured.mesh;
  const networks::FractureNetwork& network = fractured.network;

  std::string joints = "fracture,set,joint,x1,y1,x2,y2\n";
  std::string fractures = "name,set,joints,length_m,target_length_m,reached_target,seed_joint\n";
  for (const networks::GeneratedFracture& f : network.fractures) {
    const std::string& set = c.fracture_sets[f.set].name;
    for (int j : f.joints) {
      const Vec2& p = m.points[m.joints[j].point_p];
      const Vec2& q = m.points[m.joints[j].point_q];
      joints += f.name + "," + set + ",";
      append(joints, j);
      for (double v : {p.x(), p.y(), q.x(), q.y()}) {
        joints += ',';
        append(joints, v);
      }
      joints += '\n';
    }
    fractures += f.name + "," + set + ",";
    append(fractures, static_cast<int>(f.joints.size()));
    fractures += ',';
    append(fractures, f.length_m);
    fractures += ',';
    append(fractures, f.target_length_m);
    fractures += f.reached_target ? ",1," : ",0,";
    append(fractures, f.seed_joint);
    fractures += '\n';
  }
  io::write_file_atomically(dir + "/network.csv", joints);
  io::write_file_atomically(dir + "/network_fractures.csv", fractures);

  std::string sets = "name,azimuth_deg,candidates,seeds,absorbed_seeds,fractures,reaching_target,joints,total_length_m\n";
  for (std::size_t k = 0; k < network.sets.size(); ++k) {
    const networks::SetStatistics& s = network.sets[k];
    sets += c.fracture_sets[k].name + ",";
    append(sets, c.fracture_sets[k].azimuth_deg);
    for (int v : {s.candidates, s.seeds, s.absorbed_seeds, s.fractures, s.fractures_reaching_target, s.joints}) {
      sets += ',';
      append(sets, v);
    }
    sets += ',';
    append(sets, s.total_length_m);
    sets += '\n';
  }
  io::write_file_atomically(dir + "/network_sets.csv", sets);

  std::vector<std::pair<Vec2, Vec2>> lines;
  io::LineCellData set{"set", {}}, fracture{"fracture", {}}, natural{"natural", {}}, id{"joint_id", {}};
  lines.reserve(m.joints.size());
  for (std::size_t j = 0; j < m.joints.size(); ++j) {
    lines.emplace_back(m.points[m.joints[j].point_p], m.points[m.joints[j].point_q]);
    const int f = network.fracture_of_joint.empty() ? -1 : network.fracture_of_joint[j];
    set.values.push_back(f < 0 ? -1 : network.fractures[f].set);
    fracture.values.push_back(f);
    natural.values.push_back(m.joints[j].properties.natural ? 1 : 0);
    id.values.push_back(static_cast<int>(j));
  }
  io::write_lines_vtu(dir + "/network.vtu", lines, {set, fracture, natural, id});
}

}  // namespace hfdda::simulation
