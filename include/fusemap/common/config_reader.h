#ifndef FUSEMAP_COMMON_CONFIG_READER_H_
#define FUSEMAP_COMMON_CONFIG_READER_H_

#include <yaml-cpp/yaml.h>

#include <memory>
#include <set>
#include <string>
#include <vector>

#include "fusemap/common/option_checker.h"

namespace fusemap {
namespace common {

// Reads a YAML options file into plain option structs. Every key a parse function asks for is
// remembered, so that Finish() can report keys nobody asked for (typos) and values of the wrong
// type, naming the file, line and key path. Missing keys leave the struct's default in place.
// Refused outright (no reader): a directory or unreadable file, YAML syntax errors and keys
// repeated in one mapping. Numbers must be finite (.inf and .nan are errors).
class ConfigReader {
 public:
  // Loads a file; on failure returns nullptr and fills *error.
  static std::unique_ptr<ConfigReader> FromFile(const std::string& path, std::string* error);
  // For tests and for strings embedded in logs; `origin` names the source in messages.
  static std::unique_ptr<ConfigReader> FromString(const std::string& yaml, const std::string& origin,
                                                  std::string* error);

  ConfigReader(const ConfigReader&) = delete;
  ConfigReader& operator=(const ConfigReader&) = delete;

  bool Has(const std::string& key) const;

  // Reads a scalar if the key is present; a wrong type is recorded as an error.
  void Get(const std::string& key, double* value);
  void Get(const std::string& key, float* value);
  void Get(const std::string& key, int* value);
  void Get(const std::string& key, bool* value);
  void Get(const std::string& key, std::string* value);
  void Get(const std::string& key, std::vector<double>* value);

  // A nested mapping. Returns a reader over an empty map if the key is absent, so defaults hold.
  ConfigReader& Child(const std::string& key);

  // Records a semantic error (for example an out-of-range value) against `key`.
  void AddError(const std::string& key, const std::string& message);

  // Records each problem options.Check() finds in the fields read from this mapping against its
  // key (nested structs are left to their own parsers). Call at the end of a Parse function.
  template <typename Options>
  void CheckOptions(const Options& options) {
    OptionChecker check(OptionChecker::Scope::kOwnFields);
    options.Check(&check);
    for (const auto& problem : check.problems()) AddError(problem.key, problem.message);
  }

  // True if every key in the file was asked for and every value parsed; otherwise lists the
  // problems, one per line, each with file, line and key path.
  bool Finish(std::string* error) const;

 private:
  struct Shared {
    std::string origin;
    std::vector<std::string> errors;
  };
  ConfigReader(YAML::Node node, std::string path, std::shared_ptr<Shared> shared);
  std::string Where(const std::string& key) const;
  template <typename T>
  void GetScalar(const std::string& key, T* value);
  void CollectUnknown(std::vector<std::string>* errors) const;

  YAML::Node node_;
  std::string path_;
  std::shared_ptr<Shared> shared_;
  std::set<std::string> asked_;
  std::vector<std::unique_ptr<ConfigReader>> children_;
};

}  // namespace common
}  // namespace fusemap

#endif  // FUSEMAP_COMMON_CONFIG_READER_H_
