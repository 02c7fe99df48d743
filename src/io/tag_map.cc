#include "fusemap/io/tag_map.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <map>
#include <set>
#include <sstream>

namespace fusemap {
namespace io {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

std::string Where(const std::string& path, const YAML::Node& node) {
  return path + ":" + std::to_string(node.Mark().line + 1);
}

// yaml-cpp throws on malformed files and on failed conversions; io/ turns both into messages.
bool LoadYaml(const std::string& path, YAML::Node* root, std::string* error) {
  try {
    *root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    *error = path + ": cannot read file";
    return false;
  } catch (const YAML::Exception& e) {
    *error = path + ":" + std::to_string(e.mark.line + 1) + ": " + e.msg;
    return false;
  }
  if (!root->IsMap()) {
    *error = path + ": expected a YAML mapping at the top level";
    return false;
  }
  return true;
}

bool GetDouble(const std::string& path, const YAML::Node& node, double* value, std::string* error) {
  try {
    *value = node.as<double>();
  } catch (const YAML::Exception&) {
    *error = Where(path, node) + ": expected a number";
    return false;
  }
  if (!std::isfinite(*value)) {
    *error = Where(path, node) + ": expected a finite number";
    return false;
  }
  return true;
}

bool CheckKeys(const std::string& path, const YAML::Node& map, const std::set<std::string>& known,
               std::string* error) {
  for (const auto& kv : map) {
    const std::string key = kv.first.as<std::string>();
    if (known.count(key) == 0) {
      *error = Where(path, kv.first) + ": unknown key '" + key + "'";
      return false;
    }
  }
  return true;
}

bool ReadTag(const std::string& path, const YAML::Node& node, double default_size_m,
             ground_truth::SurveyedTag* tag, std::string* error) {
  if (!node.IsMap()) {
    *error = Where(path, node) + ": a tag must be a mapping like {id: 0, x_m: 0.3, y_m: 0.3}";
    return false;
  }
  if (!CheckKeys(path, node,
                 {"id", "x_m", "y_m", "z_m", "roll_deg", "pitch_deg", "yaw_deg", "size_m"},
                 error)) {
    return false;
  }
  if (!node["id"] || !node["x_m"] || !node["y_m"]) {
    *error = Where(path, node) + ": a tag needs id, x_m and y_m";
    return false;
  }
  double id = 0.0;
  if (!GetDouble(path, node["id"], &id, error)) return false;
  if (id < 0 || id != std::floor(id)) {
    *error = Where(path, node["id"]) + ": id must be a non-negative integer";
    return false;
  }
  std::map<std::string, double> v{{"x_m", 0.0},
                                  {"y_m", 0.0},
                                  {"z_m", 0.0},
                                  {"roll_deg", 0.0},
                                  {"pitch_deg", 0.0},
                                  {"yaw_deg", 0.0},
                                  {"size_m", default_size_m}};
  for (auto& [key, value] : v) {
    if (node[key] && !GetDouble(path, node[key], &value, error)) return false;
  }
  if (!(v["size_m"] > 0.0)) {
    *error = Where(path, node) + ": tag " + std::to_string(static_cast<int>(id)) +
             " has no positive size_m (and no tag_size_m default)";
    return false;
  }
  tag->id = static_cast<int>(id);
  tag->size_m = v["size_m"];
  const Eigen::Quaterniond rotation =
      Eigen::AngleAxisd(v["yaw_deg"] * kDegToRad, Eigen::Vector3d::UnitZ()) *
      Eigen::AngleAxisd(v["pitch_deg"] * kDegToRad, Eigen::Vector3d::UnitY()) *
      Eigen::AngleAxisd(v["roll_deg"] * kDegToRad, Eigen::Vector3d::UnitX());
  tag->T_map_tag = common::Rigid3d(Eigen::Vector3d(v["x_m"], v["y_m"], v["z_m"]), rotation);
  return true;
}

}  // namespace

bool ReadTagMapFile(const std::string& path, double default_tag_size_m,
                    ground_truth::TagMap* tag_map, std::string* error) {
  tag_map->clear();
  YAML::Node root;
  if (!LoadYaml(path, &root, error)) return false;
  if (!CheckKeys(path, root, {"tag_size_m", "family", "tags"}, error)) return false;
  if (root["tag_size_m"] && !GetDouble(path, root["tag_size_m"], &default_tag_size_m, error)) {
    return false;
  }
  const YAML::Node tags = root["tags"];
  if (!tags || !tags.IsSequence()) {
    *error = path + ": expected a 'tags' list";
    return false;
  }
  std::map<int, int> first_line;
  for (const YAML::Node& node : tags) {
    ground_truth::SurveyedTag tag;
    if (!ReadTag(path, node, default_tag_size_m, &tag, error)) return false;
    const int line = node.Mark().line + 1;
    const auto [it, inserted] = first_line.emplace(tag.id, line);
    if (!inserted) {
      *error = path + ":" + std::to_string(line) + ": duplicate tag id " + std::to_string(tag.id) +
               " (first listed at line " + std::to_string(it->second) + ")";
      return false;
    }
    (*tag_map)[tag.id] = tag;
  }
  return true;
}

bool WriteTagMapFile(const std::string& path, const ground_truth::TagMap& tag_map,
                     std::string* error) {
  std::ofstream out(path);
  out << std::setprecision(10);
  out << "# Surveyed AprilTags (fusemap tag map): tag frame x right, y up as printed, z out.\n";
  out << "tags:\n";
  for (const auto& [id, tag] : tag_map) {
    const Eigen::Matrix3d R = tag.T_map_tag.rotation().toRotationMatrix();
    // ZYX Euler angles, the inverse of the reader's Rz(yaw) Ry(pitch) Rx(roll).
    const double pitch = std::asin(std::max(-1.0, std::min(1.0, -R(2, 0))));
    const double roll = std::atan2(R(2, 1), R(2, 2));
    const double yaw = std::atan2(R(1, 0), R(0, 0));
    const Eigen::Vector3d& t = tag.T_map_tag.translation();
    out << "  - {id: " << id << ", x_m: " << t.x() << ", y_m: " << t.y() << ", z_m: " << t.z()
        << ", roll_deg: " << roll / kDegToRad << ", pitch_deg: " << pitch / kDegToRad
        << ", yaw_deg: " << yaw / kDegToRad << ", size_m: " << tag.size_m << "}\n";
  }
  if (!out.good()) {
    *error = path + ": cannot write file";
    return false;
  }
  return true;
}

bool ReadMeasuresFile(const std::string& path, std::vector<ground_truth::MapMeasure>* measures,
                      std::string* error) {
  measures->clear();
  YAML::Node root;
  if (!LoadYaml(path, &root, error)) return false;
  if (!CheckKeys(path, root, {"points", "measures"}, error)) return false;
  const YAML::Node points = root["points"];
  const YAML::Node list = root["measures"];
  if (!points || !points.IsMap() || !list || !list.IsSequence()) {
    *error = path + ": expected a 'points' mapping and a 'measures' list";
    return false;
  }
  std::map<std::string, Eigen::Vector2d> named;
  for (const auto& kv : points) {
    const YAML::Node& xy = kv.second;
    Eigen::Vector2d p;
    if (!xy.IsSequence() || xy.size() != 2 || !GetDouble(path, xy[0], &p.x(), error) ||
        !GetDouble(path, xy[1], &p.y(), error)) {
      *error = Where(path, kv.first) + ": a point must be [x, y] in metres";
      return false;
    }
    named[kv.first.as<std::string>()] = p;
  }
  for (const YAML::Node& node : list) {
    if (!node.IsMap()) {
      *error = Where(path, node) + ": a measure must be a mapping {from, to, distance_m}";
      return false;
    }
    if (!CheckKeys(path, node, {"from", "to", "distance_m"}, error)) return false;
    if (!node["from"] || !node["to"] || !node["distance_m"]) {
      *error = Where(path, node) + ": a measure needs from, to and distance_m";
      return false;
    }
    ground_truth::MapMeasure m;
    m.from = node["from"].as<std::string>();
    m.to = node["to"].as<std::string>();
    if (!GetDouble(path, node["distance_m"], &m.measured_m, error)) return false;
    for (const auto& [name, where] : {std::pair{m.from, &m.from_map}, {m.to, &m.to_map}}) {
      const auto it = named.find(name);
      if (it == named.end()) {
        *error = Where(path, node) + ": unknown point '" + name + "'";
        return false;
      }
      *where = it->second;
    }
    measures->push_back(m);
  }
  return true;
}

bool WriteTagSightingsFile(const std::string& path,
                           const std::vector<ground_truth::TagSighting>& sightings,
                           std::string* error) {
  std::ofstream out(path);
  out << "# stamp_s tag_id x y z qx qy qz qw  (T_map_base seen through one tag)\n";
  out << std::fixed;
  for (const auto& s : sightings) {
    const Eigen::Vector3d& t = s.T_map_base.translation();
    const Eigen::Quaterniond& q = s.T_map_base.rotation();
    out << std::setprecision(6) << s.stamp_s << ' ' << s.tag_id << std::setprecision(9) << ' '
        << t.x() << ' ' << t.y() << ' ' << t.z() << ' ' << q.x() << ' ' << q.y() << ' ' << q.z()
        << ' ' << q.w() << '\n';
  }
  if (!out.good()) {
    *error = path + ": cannot write file";
    return false;
  }
  return true;
}

bool ReadTagSightingsFile(const std::string& path,
                          std::vector<ground_truth::TagSighting>* sightings, std::string* error) {
  sightings->clear();
  std::ifstream in(path);
  if (!in) {
    *error = path + ": cannot read file";
    return false;
  }
  std::string line;
  for (int line_number = 1; std::getline(in, line); ++line_number) {
    const size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream fields(line);
    double v[9] = {};
    int n = 0;
    while (n < 9 && fields >> v[n]) ++n;
    std::string rest;
    const Eigen::Quaterniond q(v[8], v[5], v[6], v[7]);
    if (n != 9 || (fields >> rest) || v[1] < 0 || v[1] != std::floor(v[1]) || !(q.norm() > 1e-9)) {
      *error = path + ":" + std::to_string(line_number) +
               ": expected `stamp_s tag_id x y z qx qy qz qw`";
      return false;
    }
    sightings->push_back(
        {v[0], static_cast<int>(v[1]), common::Rigid3d(Eigen::Vector3d(v[2], v[3], v[4]), q)});
  }
  return true;
}

}  // namespace io
}  // namespace fusemap
