#include "fusemap/common/command_line.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <utility>

namespace fusemap {
namespace common {
namespace {

std::string FormatNumber(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g", value);
  return text;
}

// strtoll/strtod skip leading blanks and stop at trailing text; a command-line number is the
// whole argument or nothing.
bool ParseWholeNumber(const std::string& text, int64_t* value) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text[0]))) return false;
  errno = 0;
  char* end = nullptr;
  const long long parsed = std::strtoll(text.c_str(), &end, 10);
  if (*end != '\0' || errno == ERANGE) return false;
  *value = parsed;
  return true;
}

bool ParseFiniteNumber(const std::string& text, double* value) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text[0]))) return false;
  char* end = nullptr;
  const double parsed = std::strtod(text.c_str(), &end);
  if (*end != '\0' || !std::isfinite(parsed)) return false;
  *value = parsed;
  return true;
}

// Sets *value from `text` in [min, max], or names the option and the accepted range.
template <typename Int>
bool SetWholeNumber(const std::string& name, const std::string& text, int64_t min, int64_t max,
                    Int* value, std::string* error) {
  int64_t parsed = 0;
  if (!ParseWholeNumber(text, &parsed) || parsed < min || parsed > max) {
    *error = name + ": '" + text + "' is not a whole number " +
             (max == std::numeric_limits<Int>::max()
                  ? ">= " + std::to_string(min)
                  : "in [" + std::to_string(min) + ", " + std::to_string(max) + "]");
    return false;
  }
  *value = static_cast<Int>(parsed);
  return true;
}

}  // namespace

bool NumberRange::Contains(double value) const {
  return (min_exclusive ? value > min : value >= min) && value <= max;
}

std::string NumberRange::Describe() const {
  const bool has_min = std::isfinite(min), has_max = std::isfinite(max);
  std::string text = "a finite number";
  if (has_min && has_max) {
    text += std::string(" in ") + (min_exclusive ? "(" : "[") + FormatNumber(min) + ", " +
            FormatNumber(max) + "]";
  } else if (has_min) {
    text += (min_exclusive ? " > " : " >= ") + FormatNumber(min);
  } else if (has_max) {
    text += " <= " + FormatNumber(max);
  }
  return text;
}

CommandLine::CommandLine(std::string program, std::string usage)
    : program_(std::move(program)), usage_(std::move(usage)) {}

void CommandLine::Add(Option option) { options_.push_back(std::move(option)); }

CommandLine::Option* CommandLine::Find(const std::string& name) {
  for (Option& option : options_) {
    if (option.name == name) return &option;
  }
  return nullptr;
}

void CommandLine::AddFlag(const std::string& name, bool* value, bool value_when_given) {
  Add({name, false, false, false, [value, value_when_given](const std::string&, std::string*) {
         *value = value_when_given;
         return true;
       }});
}

void CommandLine::AddString(const std::string& name, std::string* value, Required required) {
  Add({name, true, required == Required::kYes, false,
       [value](const std::string& text, std::string*) {
         *value = text;
         return true;
       }});
}

void CommandLine::AddChoice(const std::string& name, std::string* value,
                            std::vector<std::string> choices) {
  Add({name, true, false, false,
       [name, value, choices](const std::string& text, std::string* error) {
         std::string listed;
         for (const std::string& choice : choices) {
           if (choice == text) {
             *value = text;
             return true;
           }
           listed += (listed.empty() ? "" : ", ") + choice;
         }
         *error = name + ": '" + text + "' is not one of " + listed;
         return false;
       }});
}

void CommandLine::AddInt(const std::string& name, int* value, int min, int max) {
  Add({name, true, false, false,
       [name, value, min, max](const std::string& text, std::string* error) {
         return SetWholeNumber(name, text, min, max, value, error);
       }});
}

void CommandLine::AddInt64(const std::string& name, int64_t* value, int64_t min, int64_t max) {
  Add({name, true, false, false,
       [name, value, min, max](const std::string& text, std::string* error) {
         return SetWholeNumber(name, text, min, max, value, error);
       }});
}

void CommandLine::AddDouble(const std::string& name, double* value, NumberRange range) {
  Add({name, true, false, false,
       [name, value, range](const std::string& text, std::string* error) {
         double parsed = 0.0;
         if (!ParseFiniteNumber(text, &parsed) || !range.Contains(parsed)) {
           *error = name + ": '" + text + "' is not " + range.Describe();
           return false;
         }
         *value = parsed;
         return true;
       }});
}

void CommandLine::AddDoubleList(const std::string& name, std::vector<double>* values,
                                NumberRange range, size_t count) {
  Add({name, true, false, false,
       [name, values, range, count](const std::string& text, std::string* error) {
         std::vector<double> parsed;
         std::stringstream list(text);
         std::string item;
         while (std::getline(list, item, ',')) {
           double value = 0.0;
           if (!ParseFiniteNumber(item, &value) || !range.Contains(value)) {
             *error = name + ": '" + item + "' is not " + range.Describe();
             return false;
           }
           parsed.push_back(value);
         }
         // getline drops an empty last field: "1," has a missing number, not one.
         if (parsed.empty() || text.back() == ',' || (count > 0 && parsed.size() != count)) {
           *error = name + ": '" + text + "' is not " +
                    (count > 0 ? std::to_string(count) : std::string("a list of")) +
                    " comma-separated numbers";
           return false;
         }
         *values = std::move(parsed);
         return true;
       }});
}

void CommandLine::AddStringList(const std::string& name, std::vector<std::string>* values) {
  Add({name, true, false, false, [values](const std::string& text, std::string*) {
         values->push_back(text);
         return true;
       }});
}

void CommandLine::AddPositional(const std::string& name, std::string* value) {
  positionals_.emplace_back(name, value);
}

void CommandLine::AddPositionalList(const std::string& name, std::vector<std::string>* values,
                                    size_t min_count) {
  positional_list_name_ = name;
  positional_list_ = values;
  positional_list_min_ = min_count;
}

CommandLine::Status CommandLine::Parse(const std::vector<std::string>& args, std::string* error) {
  std::string first_error;
  const auto fail = [&first_error](const std::string& message) {
    if (first_error.empty()) first_error = message;
  };
  bool help = false, options_ended = false;
  size_t num_positionals = 0;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (!options_ended && arg == "--") {
      options_ended = true;
    } else if (options_ended || arg.size() < 2 || arg[0] != '-') {
      if (num_positionals < positionals_.size()) {
        *positionals_[num_positionals].second = arg;
      } else if (positional_list_ != nullptr) {
        positional_list_->push_back(arg);
      } else {
        fail("unexpected argument '" + arg + "'");
      }
      ++num_positionals;
    } else if (arg == "--help" || arg == "-h") {
      help = true;
    } else if (Option* option = Find(arg); option == nullptr) {
      fail("unknown option '" + arg + "'");
    } else if (option->takes_value && i + 1 >= args.size()) {
      fail(arg + " needs a value");
    } else {
      option->given = true;
      std::string message;
      if (!option->set(option->takes_value ? args[++i] : std::string(), &message)) fail(message);
    }
  }
  if (help) return Status::kHelp;
  if (num_positionals < positionals_.size()) {
    fail("missing " + positionals_[num_positionals].first);
  } else if (positional_list_ != nullptr &&
             num_positionals < positionals_.size() + positional_list_min_) {
    fail("missing " + positional_list_name_);
  }
  for (const Option& option : options_) {
    if (option.required && !option.given) fail("missing required option " + option.name);
  }
  if (first_error.empty()) return Status::kOk;
  *error = first_error;
  return Status::kError;
}

std::optional<int> CommandLine::ParseOrExitCode(int argc, const char* const* argv, int first) {
  return ParseOrExitCode(argc, argv, first, std::cout, std::cerr);
}

std::optional<int> CommandLine::ParseOrExitCode(int argc, const char* const* argv, int first,
                                                std::ostream& out, std::ostream& err) {
  const std::vector<std::string> args(argv + std::min(first, argc), argv + argc);
  std::string error;
  switch (Parse(args, &error)) {
    case Status::kOk:
      return std::nullopt;
    case Status::kHelp:
      out << usage_ << std::flush;
      return kExitSuccess;
    case Status::kError:
      break;
  }
  return UsageError(error, err);
}

bool CommandLine::Given(const std::string& name) const {
  for (const Option& option : options_) {
    if (option.name == name) return option.given;
  }
  return false;
}

int CommandLine::UsageError(const std::string& message) const {
  return UsageError(message, std::cerr);
}

int CommandLine::UsageError(const std::string& message, std::ostream& err) const {
  err << program_ << ": " << message << "\n" << usage_ << std::flush;
  return kExitUsage;
}

int RunSubcommand(const std::string& program, const std::string& usage,
                  const std::vector<Subcommand>& commands, int argc, char** argv) {
  return RunSubcommand(program, usage, commands, argc, argv, std::cout, std::cerr);
}

int RunSubcommand(const std::string& program, const std::string& usage,
                  const std::vector<Subcommand>& commands, int argc, char** argv,
                  std::ostream& out, std::ostream& err) {
  if (argc < 2) {
    err << program << ": missing command\n" << usage << std::flush;
    return kExitUsage;
  }
  const std::string command = argv[1];
  if (command == "--help" || command == "-h") {
    out << usage << std::flush;
    return kExitSuccess;
  }
  for (const Subcommand& subcommand : commands) {
    if (subcommand.name == command) return subcommand.run(argc, argv);
  }
  err << program << ": unknown command '" << command << "'\n" << usage << std::flush;
  return kExitUsage;
}

}  // namespace common
}  // namespace fusemap
