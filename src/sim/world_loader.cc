#include "fusemap/sim/world_loader.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <map>
#include <set>
#include <sstream>

#include "fusemap/common/math.h"
#include "texture.h"

namespace fusemap {
namespace sim {
namespace {

// Parses with yaml-cpp; the first problem wins and is reported with its line.
class Parser {
 public:
  explicit Parser(std::string origin) : origin_(std::move(origin)) {}

  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }

  void Fail(const YAML::Node& node, const std::string& message) {
    if (!error_.empty()) return;
    std::ostringstream out;
    out << origin_ << ":" << (node.Mark().line + 1) << ": " << message;
    error_ = out.str();
  }

  // Rejects keys outside `allowed`: typos should not silently fall back to defaults.
  void CheckKeys(const YAML::Node& node, const std::set<std::string>& allowed) {
    if (!node.IsMap()) return Fail(node, "expected a mapping");
    for (const auto& kv : node) {
      const std::string key = kv.first.as<std::string>();
      if (allowed.count(key) == 0) Fail(kv.first, "unknown key '" + key + "'");
    }
  }

  double Number(const YAML::Node& node, const std::string& key, double fallback, double lo = -1e9,
                double hi = 1e9) {
    const YAML::Node value = node[key];
    if (!value) return fallback;
    double result = fallback;
    try {
      result = value.as<double>();
    } catch (const YAML::Exception&) {
      Fail(value, "'" + key + "' must be a number");
      return fallback;
    }
    if (!std::isfinite(result) || result < lo || result > hi) {
      std::ostringstream out;
      out << "'" << key << "' = " << result << " is outside [" << lo << ", " << hi << "]";
      Fail(value, out.str());
    }
    return result;
  }

  std::vector<double> Numbers(const YAML::Node& node, size_t count) {
    std::vector<double> values;
    if (!node.IsSequence() || node.size() != count) {
      Fail(node, "expected a list of " + std::to_string(count) + " numbers");
      return std::vector<double>(count, 0.0);
    }
    for (const auto& item : node) {
      try {
        values.push_back(item.as<double>());
      } catch (const YAML::Exception&) {
        Fail(item, "expected a number");
        values.push_back(0.0);
      }
    }
    return values;
  }

  Eigen::Vector2d Point(const YAML::Node& node, const std::string& key) {
    if (!node[key]) {
      Fail(node, "missing '" + key + "'");
      return Eigen::Vector2d::Zero();
    }
    const std::vector<double> v = Numbers(node[key], 2);
    return Eigen::Vector2d(v[0], v[1]);
  }

  Eigen::Vector3f Color(const YAML::Node& node, const std::string& key, const Eigen::Vector3f& fallback) {
    if (!node[key]) return fallback;
    const std::vector<double> v = Numbers(node[key], 3);
    for (double c : v) {
      if (c < 0.0 || c > 255.0) Fail(node[key], "colour components must be in [0, 255]");
    }
    return Eigen::Vector3f(v[0], v[1], v[2]);
  }

  Texture ParseTexture(const YAML::Node& node) {
    Texture texture;
    CheckKeys(node, {"kind", "seed", "scale_m", "color_a", "color_b", "band_m"});
    if (!ok()) return texture;
    const std::string kind = node["kind"] ? node["kind"].as<std::string>() : "plain";
    if (!TextureKindFromName(kind, &texture.kind)) Fail(node, "unknown texture kind '" + kind + "'");
    texture.seed = static_cast<uint32_t>(Number(node, "seed", 0, 0, 4e9));
    texture.scale_m = Number(node, "scale_m", texture.scale_m, 0.01, 10.0);
    texture.color_a = Color(node, "color_a", texture.color_a);
    texture.color_b = Color(node, "color_b", texture.color_b);
    if (node["band_m"]) {
      const std::vector<double> band = Numbers(node["band_m"], 2);
      if (!(band[0] >= 0.0 && band[1] >= band[0] + 0.1 && band[1] <= 50.0)) {
        Fail(node["band_m"], "band_m needs 0 <= bottom and bottom + 0.1 <= top <= 50");
      }
      texture.band_bottom_m = band[0];
      texture.band_top_m = band[1];
    }
    return texture;
  }

  // A texture given inline or by name from the world's `textures` section.
  Texture TextureRef(const YAML::Node& node, const std::string& key) {
    const YAML::Node value = node[key];
    if (!value) return Texture();
    if (value.IsMap()) return ParseTexture(value);
    const std::string name = value.as<std::string>();
    const auto it = named_.find(name);
    if (it == named_.end()) {
      Fail(value, "unknown texture '" + name + "'");
      return Texture();
    }
    return it->second;
  }

  std::map<std::string, Texture> named_;

 private:
  std::string origin_;
  std::string error_;
};

void ParseWorld(const YAML::Node& root, Parser* p, World* world) {
  p->CheckKeys(root, {"name", "ceiling_height_m", "floor", "textures", "walls", "pillars", "boxes",
                      "tags", "people", "depth_dropout_zones", "lighting", "robot"});
  if (!p->ok()) return;
  world->name = root["name"] ? root["name"].as<std::string>() : "";
  world->ceiling_height_m = p->Number(root, "ceiling_height_m", world->ceiling_height_m, 1.0, 50.0);
  if (const YAML::Node floor = root["floor"]) {
    p->CheckKeys(floor, {"tile_m", "color", "seed"});
    world->floor_tile_m = p->Number(floor, "tile_m", world->floor_tile_m, 0.05, 10.0);
    world->floor_color = p->Color(floor, "color", world->floor_color);
    world->floor_seed = static_cast<uint32_t>(p->Number(floor, "seed", world->floor_seed, 0, 4e9));
  }
  for (const auto& kv : root["textures"]) p->named_[kv.first.as<std::string>()] = p->ParseTexture(kv.second);

  for (const YAML::Node& wall : root["walls"]) {
    p->CheckKeys(wall, {"from", "to", "thickness_m", "height_m", "texture"});
    const Eigen::Vector2d a = p->Point(wall, "from"), b = p->Point(wall, "to");
    const double thickness = p->Number(wall, "thickness_m", 0.2, 0.01, 10.0);
    if ((b - a).norm() < 1e-6) p->Fail(wall, "wall has zero length");
    Prism prism;
    prism.centre_m = 0.5 * (a + b);
    prism.yaw_rad = std::atan2(b.y() - a.y(), b.x() - a.x());
    // Extend by half the thickness so walls meeting at a corner close it.
    prism.half_size_m = Eigen::Vector2d(0.5 * ((b - a).norm() + thickness), 0.5 * thickness);
    prism.z_max_m = p->Number(wall, "height_m", world->ceiling_height_m, 0.01, 50.0);
    prism.side_textures.fill(p->TextureRef(wall, "texture"));
    prism.top_texture = prism.side_textures[0];
    world->prisms.push_back(prism);
  }
  for (const YAML::Node& pillar : root["pillars"]) {
    p->CheckKeys(pillar, {"centre", "radius_m", "height_m", "texture"});
    Prism prism;
    prism.shape = Prism::Shape::kCircle;
    prism.centre_m = p->Point(pillar, "centre");
    prism.radius_m = p->Number(pillar, "radius_m", 0.3, 0.01, 100.0);
    prism.z_max_m = p->Number(pillar, "height_m", world->ceiling_height_m, 0.01, 50.0);
    prism.side_textures.fill(p->TextureRef(pillar, "texture"));
    prism.top_texture = prism.side_textures[0];
    world->prisms.push_back(prism);
  }
  for (const YAML::Node& box : root["boxes"]) {
    p->CheckKeys(box, {"centre", "size", "yaw_deg", "texture", "side_textures", "top_texture"});
    Prism prism;
    prism.centre_m = p->Point(box, "centre");
    const std::vector<double> size = box["size"] ? p->Numbers(box["size"], 3) : std::vector<double>{1, 1, 1};
    for (double s : size) {
      if (s <= 0.0) p->Fail(box, "box size must be positive");
    }
    prism.half_size_m = Eigen::Vector2d(0.5 * size[0], 0.5 * size[1]);
    prism.z_max_m = size[2];
    prism.yaw_rad = common::DegToRad(p->Number(box, "yaw_deg", 0.0, -360.0, 360.0));
    prism.side_textures.fill(p->TextureRef(box, "texture"));
    prism.top_texture = box["top_texture"] ? p->TextureRef(box, "top_texture") : prism.side_textures[0];
    if (const YAML::Node sides = box["side_textures"]) {
      if (!sides.IsSequence() || sides.size() != 4) {
        p->Fail(sides, "side_textures needs 4 entries (+x, +y, -x, -y faces)");
      } else {
        for (int i = 0; i < 4; ++i) {
          YAML::Node wrapper;
          wrapper["t"] = sides[i];
          prism.side_textures[i] = p->TextureRef(wrapper, "t");
        }
      }
    }
    world->prisms.push_back(prism);
  }
  for (const YAML::Node& tag : root["tags"]) {
    p->CheckKeys(tag, {"id", "x", "y", "yaw_deg", "size_m"});
    FloorTag t;
    t.id = static_cast<int>(p->Number(tag, "id", -1, 0, 586));
    t.x_m = p->Number(tag, "x", 0.0);
    t.y_m = p->Number(tag, "y", 0.0);
    t.yaw_rad = common::DegToRad(p->Number(tag, "yaw_deg", 0.0, -360.0, 360.0));
    t.size_m = p->Number(tag, "size_m", t.size_m, 0.02, 5.0);
    world->tags.push_back(t);
  }
  for (const YAML::Node& person : root["people"]) {
    p->CheckKeys(person, {"path", "speed_mps", "radius_m", "height_m", "texture"});
    Person q;
    for (const YAML::Node& point : person["path"]) {
      const std::vector<double> v = p->Numbers(point, 2);
      q.path_m.emplace_back(v[0], v[1]);
    }
    if (q.path_m.empty()) p->Fail(person, "person needs a non-empty 'path'");
    q.speed_mps = p->Number(person, "speed_mps", q.speed_mps, 0.0, 10.0);
    q.radius_m = p->Number(person, "radius_m", q.radius_m, 0.05, 2.0);
    q.height_m = p->Number(person, "height_m", q.height_m, 0.1, 3.0);
    q.texture = p->TextureRef(person, "texture");
    world->people.push_back(q);
  }
  for (const YAML::Node& zone : root["depth_dropout_zones"]) {
    p->CheckKeys(zone, {"min", "max"});
    DepthDropoutZone z{p->Point(zone, "min"), p->Point(zone, "max")};
    if (!(z.min_m.array() < z.max_m.array()).all()) p->Fail(zone, "zone needs min < max");
    world->depth_dropout_zones.push_back(z);
  }
  for (const YAML::Node& phase : root["lighting"]) {
    p->CheckKeys(phase, {"from_lap", "gain", "bias", "noise_std"});
    LightingPhase l;
    l.from_lap = p->Number(phase, "from_lap", l.from_lap, 0.0, 1000.0);
    l.gain = p->Number(phase, "gain", l.gain, 0.05, 10.0);
    l.bias = p->Number(phase, "bias", l.bias, -255.0, 255.0);
    l.noise_std = p->Number(phase, "noise_std", l.noise_std, 0.0, 100.0);
    if (!world->lighting.empty() && l.from_lap <= world->lighting.back().from_lap) {
      p->Fail(phase, "lighting phases need increasing from_lap");
    }
    world->lighting.push_back(l);
  }
  const YAML::Node robot = root["robot"];
  if (!robot) return p->Fail(root, "missing 'robot'");
  p->CheckKeys(robot, {"waypoints", "max_speed_mps", "max_accel_mps2", "max_lateral_accel_mps2",
                       "turn_radius_m", "laps", "odometry_speed_scale"});
  for (const YAML::Node& point : robot["waypoints"]) {
    const std::vector<double> v = p->Numbers(point, 2);
    world->robot.waypoints_m.emplace_back(v[0], v[1]);
  }
  const auto& w = world->robot.waypoints_m;
  if (w.size() < 3) p->Fail(robot, "robot needs at least 3 waypoints");
  for (size_t i = 0; i < w.size(); ++i) {
    if ((w[i] - w[(i + 1) % w.size()]).norm() < 0.1) p->Fail(robot, "consecutive waypoints closer than 0.1 m");
  }
  RobotPlan& plan = world->robot;
  plan.max_speed_mps = p->Number(robot, "max_speed_mps", plan.max_speed_mps, 0.05, 10.0);
  plan.max_accel_mps2 = p->Number(robot, "max_accel_mps2", plan.max_accel_mps2, 0.05, 20.0);
  plan.max_lateral_accel_mps2 = p->Number(robot, "max_lateral_accel_mps2", plan.max_lateral_accel_mps2, 0.05, 20.0);
  plan.turn_radius_m = p->Number(robot, "turn_radius_m", plan.turn_radius_m, 0.05, 100.0);
  plan.laps = p->Number(robot, "laps", plan.laps, 0.01, 1000.0);
  plan.odometry_speed_scale =
      p->Number(robot, "odometry_speed_scale", plan.odometry_speed_scale, 0.5, 1.5);
}

}  // namespace

bool LoadWorldFromString(const std::string& yaml, const std::string& origin, World* world,
                         std::string* error) {
  *world = World();
  Parser parser(origin);
  try {
    ParseWorld(YAML::Load(yaml), &parser, world);
  } catch (const YAML::Exception& e) {
    *error = origin + ":" + std::to_string(e.mark.line + 1) + ": " + e.msg;
    return false;
  }
  if (!parser.ok()) *error = parser.error();
  return parser.ok();
}

bool LoadWorldFile(const std::string& path, World* world, std::string* error) {
  std::ifstream in(path);
  if (!in) {
    *error = path + ": cannot open";
    return false;
  }
  std::stringstream buffer;
  buffer << in.rdbuf();
  return LoadWorldFromString(buffer.str(), path, world, error);
}

std::string TagMapYaml(const std::vector<FloorTag>& tags) {
  std::ostringstream out;
  out << std::setprecision(9);
  // The layout io::ReadTagMapFile (fusemap_tagscore) reads: a list of surveyed tags, the tag
  // frame with x along the printed image's columns, y up the printed image, z out of the floor.
  out << "# Floor AprilTags written by fusemap_sim: centre x_m, y_m (world frame), yaw_deg,\n"
         "# size_m = black square edge.\n";
  out << "family: tag36h11\ntags:\n";
  for (const FloorTag& tag : tags) {
    out << "  - {id: " << tag.id << ", x_m: " << tag.x_m << ", y_m: " << tag.y_m
        << ", yaw_deg: " << tag.yaw_rad * 180.0 / 3.14159265358979323846
        << ", size_m: " << tag.size_m << "}\n";
  }
  return out.str();
}

bool WriteTagMapFile(const std::string& path, const std::vector<FloorTag>& tags, std::string* error) {
  std::ofstream out(path);
  out << TagMapYaml(tags);
  if (!out) {
    *error = path + ": cannot write";
    return false;
  }
  return true;
}

}  // namespace sim
}  // namespace fusemap
