#include "fusemap/common/config_reader.h"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace fusemap {
namespace common {
namespace {

std::string Line(const YAML::Node& node) {
  return node.Mark().line >= 0 ? std::to_string(node.Mark().line + 1) : "?";
}

// yaml-cpp keeps every pair of a mapping but looks keys up by their first occurrence, so a
// repeated key would silently lose its later value: walk the tree and name each repetition.
void FindDuplicateKeys(const YAML::Node& node, const std::string& path, const std::string& origin,
                       std::vector<std::string>* errors) {
  if (node.IsSequence()) {
    for (size_t i = 0; i < node.size(); ++i) {
      FindDuplicateKeys(node[i], path + "[" + std::to_string(i) + "].", origin, errors);
    }
    return;
  }
  if (!node.IsMap()) return;
  std::map<std::string, std::string> first_line;
  for (const auto& kv : node) {
    const std::string key = kv.first.Scalar();
    const auto inserted = first_line.emplace(key, Line(kv.first));
    if (!inserted.second) {
      errors->push_back(origin + ":" + Line(kv.first) + ": key '" + path + key +
                        "' appears again (first on line " + inserted.first->second + ")");
    }
    FindDuplicateKeys(kv.second, path + key + ".", origin, errors);
  }
}

bool IsFinite(double value) { return std::isfinite(value); }
bool IsFinite(float value) { return std::isfinite(value); }
bool IsFinite(const std::vector<double>& values) {
  for (double v : values) {
    if (!std::isfinite(v)) return false;
  }
  return true;
}
template <typename T>
bool IsFinite(const T&) {
  return true;
}

}  // namespace

ConfigReader::ConfigReader(YAML::Node node, std::string path, std::shared_ptr<Shared> shared)
    : node_(std::move(node)), path_(std::move(path)), shared_(std::move(shared)) {}

std::unique_ptr<ConfigReader> ConfigReader::FromString(const std::string& yaml,
                                                       const std::string& origin,
                                                       std::string* error) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml);
  } catch (const YAML::Exception& e) {
    *error = origin + ":" + std::to_string(e.mark.line + 1) + ": YAML syntax error: " + e.msg;
    return nullptr;
  }
  if (!root.IsNull() && !root.IsMap()) {
    *error = origin + ": top level must be a mapping of option names to values";
    return nullptr;
  }
  if (root.IsNull()) root = YAML::Node(YAML::NodeType::Map);
  std::vector<std::string> duplicates;
  FindDuplicateKeys(root, "", origin, &duplicates);
  if (!duplicates.empty()) {
    std::string joined;
    for (const auto& e : duplicates) joined += (joined.empty() ? "" : "\n") + e;
    *error = joined;
    return nullptr;
  }
  auto shared = std::make_shared<Shared>();
  shared->origin = origin;
  return std::unique_ptr<ConfigReader>(new ConfigReader(root, "", shared));
}

std::unique_ptr<ConfigReader> ConfigReader::FromFile(const std::string& path, std::string* error) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    *error = path + ": is a directory, not a config file";
    return nullptr;
  }
  std::ifstream in(path);
  if (!in) {
    *error = path + ": cannot open config file (" + std::strerror(errno) + ")";
    return nullptr;
  }
  std::stringstream ss;
  ss << in.rdbuf();
  if (in.bad()) {
    *error = path + ": cannot read config file";
    return nullptr;
  }
  return FromString(ss.str(), path, error);
}

bool ConfigReader::Has(const std::string& key) const { return node_[key].IsDefined(); }

std::string ConfigReader::Where(const std::string& key) const {
  std::string line;
  const YAML::Node n = node_[key];
  if (n.IsDefined() && n.Mark().line >= 0) line = ":" + std::to_string(n.Mark().line + 1);
  return shared_->origin + line + ": key '" + path_ + key + "'";
}

template <typename T>
void ConfigReader::GetScalar(const std::string& key, T* value) {
  asked_.insert(key);
  const YAML::Node n = node_[key];
  if (!n.IsDefined() || n.IsNull()) return;
  T parsed;
  try {
    parsed = n.as<T>();
  } catch (const YAML::Exception&) {
    shared_->errors.push_back(Where(key) + ": value has the wrong type");
    return;
  }
  // No option means infinity or NaN; .inf/.nan in a file is a mistake that would otherwise
  // surface as a hang or a crash far from here.
  if (!IsFinite(parsed)) {
    shared_->errors.push_back(Where(key) + ": value must be a finite number");
    return;
  }
  *value = std::move(parsed);
}

void ConfigReader::Get(const std::string& key, double* value) { GetScalar(key, value); }
void ConfigReader::Get(const std::string& key, float* value) { GetScalar(key, value); }
void ConfigReader::Get(const std::string& key, int* value) { GetScalar(key, value); }
void ConfigReader::Get(const std::string& key, bool* value) { GetScalar(key, value); }
void ConfigReader::Get(const std::string& key, std::string* value) { GetScalar(key, value); }
void ConfigReader::Get(const std::string& key, std::vector<double>* value) {
  GetScalar(key, value);
}

ConfigReader& ConfigReader::Child(const std::string& key) {
  asked_.insert(key);
  YAML::Node n = node_[key];
  if (n.IsDefined() && !n.IsNull() && !n.IsMap()) {
    shared_->errors.push_back(Where(key) + ": expected a mapping");
    n = YAML::Node(YAML::NodeType::Map);
  }
  if (!n.IsDefined() || n.IsNull()) n = YAML::Node(YAML::NodeType::Map);
  children_.push_back(std::unique_ptr<ConfigReader>(new ConfigReader(n, path_ + key + ".", shared_)));
  return *children_.back();
}

void ConfigReader::AddError(const std::string& key, const std::string& message) {
  shared_->errors.push_back(Where(key) + ": " + message);
}

void ConfigReader::CollectUnknown(std::vector<std::string>* errors) const {
  for (const auto& kv : node_) {
    const std::string key = kv.first.as<std::string>();
    if (!asked_.count(key)) errors->push_back(Where(key) + ": unknown option");
  }
  for (const auto& child : children_) child->CollectUnknown(errors);
}

bool ConfigReader::Finish(std::string* error) const {
  std::vector<std::string> errors = shared_->errors;
  CollectUnknown(&errors);
  if (errors.empty()) return true;
  std::string joined;
  for (const auto& e : errors) joined += (joined.empty() ? "" : "\n") + e;
  *error = joined;
  return false;
}

}  // namespace common
}  // namespace fusemap
