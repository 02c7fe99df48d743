#ifndef FUSEMAP_COMMON_COMMAND_LINE_H_
#define FUSEMAP_COMMON_COMMAND_LINE_H_

#include <cstdint>
#include <functional>
#include <iosfwd>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace fusemap {
namespace common {

// Exit codes of every binary (README "Exit codes"); fusemapd adds 3 for a checkpoint that
// cannot be restored.
constexpr int kExitSuccess = 0;
constexpr int kExitFailure = 1;  // bad input or a failed run
constexpr int kExitUsage = 2;    // command-line usage error

// The values a number option accepts besides being finite: [min, max], or (min, max] when
// `min_exclusive`.
struct NumberRange {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_exclusive = false;

  static NumberRange Positive() { return {0.0, std::numeric_limits<double>::infinity(), true}; }
  static NumberRange NonNegative() { return {0.0, std::numeric_limits<double>::infinity(), false}; }
  bool Contains(double value) const;
  // "a finite number > 0", "a finite number in (0, 100]": the words of an error message.
  std::string Describe() const;
};

// A program's command line: options and positional arguments declared with the variables they
// fill, then parsed once. `--name value` options take the next argument verbatim (it may start
// with '-'); a repeated option keeps its last value unless declared as a list. `--help`/`-h`
// anywhere asks for the usage text, and wins over errors elsewhere on the line. An argument
// starting with '-' (other than "-") is an option; after "--" everything is positional.
// Declared variables keep their defaults unless the option is given. Not copyable: the
// declarations point at the caller's variables.
class CommandLine {
 public:
  enum class Status { kOk, kHelp, kError };
  enum class Required { kNo, kYes };

  // `program` starts every error line ("fusemap_eval ate: ..."); `usage` is printed verbatim
  // by --help and after an error.
  CommandLine(std::string program, std::string usage);
  CommandLine(const CommandLine&) = delete;
  CommandLine& operator=(const CommandLine&) = delete;

  // --name without a value: sets *value to `value_when_given`.
  void AddFlag(const std::string& name, bool* value, bool value_when_given = true);
  void AddString(const std::string& name, std::string* value, Required required = Required::kNo);
  // A string that must be one of `choices`.
  void AddChoice(const std::string& name, std::string* value, std::vector<std::string> choices);
  // Whole numbers in [min, max] (decimal; no fraction, exponent or trailing text).
  void AddInt(const std::string& name, int* value, int min, int max);
  void AddInt64(const std::string& name, int64_t* value, int64_t min, int64_t max);
  // A finite number within `range`.
  void AddDouble(const std::string& name, double* value, NumberRange range = {});
  // Comma-separated finite numbers within `range`, replacing *values; exactly `count` of them
  // unless `count` is 0.
  void AddDoubleList(const std::string& name, std::vector<double>* values, NumberRange range = {},
                     size_t count = 0);
  // A repeatable option: every occurrence appends its value.
  void AddStringList(const std::string& name, std::vector<std::string>* values);
  // Required positional arguments, filled in declaration order ...
  void AddPositional(const std::string& name, std::string* value);
  // ... and then the rest, at least `min_count` of them. Without a list, extra ones are errors.
  void AddPositionalList(const std::string& name, std::vector<std::string>* values,
                         size_t min_count);

  // Parses `args` (without the program name). On kError, *error is one line naming the option
  // or argument.
  Status Parse(const std::vector<std::string>& args, std::string* error);
  // Parses argv[first..] and decides what a main does next: nullopt to go on; otherwise the exit
  // code after printing: 0 with the usage on `out` (--help), 2 with "program: error" and the
  // usage on `err`.
  std::optional<int> ParseOrExitCode(int argc, const char* const* argv, int first = 1);
  std::optional<int> ParseOrExitCode(int argc, const char* const* argv, int first,
                                     std::ostream& out, std::ostream& err);

  // Whether the option was on the command line (its variable may hold the default otherwise).
  bool Given(const std::string& name) const;
  // For checks across options after parsing: prints "program: message" and the usage to `err`
  // and returns kExitUsage.
  int UsageError(const std::string& message) const;
  int UsageError(const std::string& message, std::ostream& err) const;

 private:
  struct Option {
    std::string name;
    bool takes_value = true;
    bool required = false;
    bool given = false;
    // Stores the value (or sets the flag); false with *error naming the option if it is bad.
    std::function<bool(const std::string& text, std::string* error)> set;
  };

  void Add(Option option);
  Option* Find(const std::string& name);

  std::string program_;
  std::string usage_;
  std::vector<Option> options_;
  std::vector<std::pair<std::string, std::string*>> positionals_;
  std::string positional_list_name_;
  std::vector<std::string>* positional_list_ = nullptr;
  size_t positional_list_min_ = 0;
};

// A program with subcommands ("fusemap_eval ate ..."): argv[1] picks one of `commands`, which
// parses argv[2..] itself. "--help"/"-h" there prints `usage` (exit 0); a missing or unknown
// command prints an error line and `usage` to stderr (exit 2).
struct Subcommand {
  std::string name;
  std::function<int(int argc, char** argv)> run;
};
int RunSubcommand(const std::string& program, const std::string& usage,
                  const std::vector<Subcommand>& commands, int argc, char** argv);
int RunSubcommand(const std::string& program, const std::string& usage,
                  const std::vector<Subcommand>& commands, int argc, char** argv,
                  std::ostream& out, std::ostream& err);

}  // namespace common
}  // namespace fusemap

#endif  // FUSEMAP_COMMON_COMMAND_LINE_H_
