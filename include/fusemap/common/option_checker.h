#ifndef FUSEMAP_COMMON_OPTION_CHECKER_H_
#define FUSEMAP_COMMON_OPTION_CHECKER_H_

#include <string>
#include <utility>
#include <vector>

namespace fusemap {
namespace common {

// Collects what is wrong with an options struct, each problem against the key that holds the bad
// value. Every options struct has
//   void Check(common::OptionChecker* check) const;
// which states each field's rule once, with Require(), and hands nested structs to Nested(). Its
// parser reports the problems through ConfigReader::CheckOptions(), so a config error names the
// full key path and its file:line; IsValid() reports the first one, naming the field, for options
// built in C++.
class OptionChecker {
 public:
  struct Problem {
    std::string key;      // relative to the checked struct: "ceres_scan_matcher.num_threads"
    std::string message;  // what the value must be: "must be >= 1"
  };

  // A parser checks only the fields it read itself: each nested struct was checked by its own
  // parser, against its own mapping, before.
  enum class Scope { kOwnFields, kWithNested };

  explicit OptionChecker(Scope scope = Scope::kWithNested) : scope_(scope) {}

  // Records `message` against `key` unless `ok`; returns `ok`.
  bool Require(bool ok, const std::string& key, const std::string& message) {
    if (!ok) problems_.push_back({key, message});
    return ok;
  }

  // Checks `nested`, the options read from the mapping `key`, naming its keys "key.<its key>".
  template <typename Options>
  void Nested(const std::string& key, const Options& nested) {
    if (scope_ == Scope::kOwnFields) return;
    OptionChecker inner(scope_);
    nested.Check(&inner);
    for (Problem& problem : inner.problems_) {
      problems_.push_back({key + "." + problem.key, std::move(problem.message)});
    }
  }

  const std::vector<Problem>& problems() const { return problems_; }

 private:
  Scope scope_;
  std::vector<Problem> problems_;
};

// The body of every options struct's IsValid(): true, or false with "<key> <message>" of the
// first problem in *error (if error is not null).
template <typename Options>
bool IsValidOptions(const Options& options, std::string* error) {
  OptionChecker check;
  options.Check(&check);
  if (check.problems().empty()) return true;
  const OptionChecker::Problem& first = check.problems().front();
  if (error != nullptr) *error = first.key + " " + first.message;
  return false;
}

}  // namespace common
}  // namespace fusemap

#endif  // FUSEMAP_COMMON_OPTION_CHECKER_H_
