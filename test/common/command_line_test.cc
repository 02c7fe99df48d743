#include "fusemap/common/command_line.h"

#include <gtest/gtest.h>

#include <sstream>

namespace fusemap {
namespace common {
namespace {

using Status = CommandLine::Status;

constexpr char kUsage[] = "usage: prog IN [--out FILE] [--threads N] [--scale S] [--quiet]\n";

// The declarations of a typical tool, with its defaults.
struct Args {
  std::string in, out = "default.txt";
  int threads = 1;
  double scale = 1.0;
  bool quiet = false;
};

void Declare(CommandLine* command_line, Args* args) {
  command_line->AddPositional("IN", &args->in);
  command_line->AddString("--out", &args->out);
  command_line->AddInt("--threads", &args->threads, 1, 64);
  command_line->AddDouble("--scale", &args->scale, NumberRange::Positive());
  command_line->AddFlag("--quiet", &args->quiet);
}

Status Parse(const std::vector<std::string>& argv, Args* args, std::string* error) {
  CommandLine command_line("prog", kUsage);
  Declare(&command_line, args);
  return command_line.Parse(argv, error);
}

TEST(CommandLineTest, FillsDeclaredVariablesAndKeepsDefaults) {
  Args args;
  std::string error;
  ASSERT_EQ(Parse({"in.log", "--threads", "4", "--quiet"}, &args, &error), Status::kOk) << error;
  EXPECT_EQ(args.in, "in.log");
  EXPECT_EQ(args.out, "default.txt");
  EXPECT_EQ(args.threads, 4);
  EXPECT_EQ(args.scale, 1.0);
  EXPECT_TRUE(args.quiet);
}

TEST(CommandLineTest, ValuesAreTakenVerbatimAndTheLastRepetitionWins) {
  Args args;
  std::string error;
  ASSERT_EQ(Parse({"--out", "-dash.txt", "--threads", "2", "in", "--threads", "64", "--scale",
                   "2.5e-1"},
                  &args, &error),
            Status::kOk)
      << error;
  EXPECT_EQ(args.out, "-dash.txt");
  EXPECT_EQ(args.threads, 64);
  EXPECT_EQ(args.scale, 0.25);
}

TEST(CommandLineTest, HelpWinsAnywhereEvenAfterAnError) {
  for (const std::vector<std::string>& argv :
       std::vector<std::vector<std::string>>{{"--help"}, {"-h"}, {"--bogus", "--help"},
                                             {"in", "--threads", "0", "-h"}}) {
    Args args;
    std::string error;
    EXPECT_EQ(Parse(argv, &args, &error), Status::kHelp) << argv[0];
  }
}

TEST(CommandLineTest, UsageErrorsNameTheOption) {
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"in", "--bogus"}, "unknown option '--bogus'"},
      {{"in", "--out"}, "--out needs a value"},
      {{"in", "--threads", "x"}, "--threads: 'x' is not a whole number in [1, 64]"},
      {{"in", "--threads", "65"}, "--threads: '65' is not a whole number in [1, 64]"},
      {{"in", "--threads", "2.5"}, "--threads: '2.5' is not a whole number in [1, 64]"},
      {{"in", "--threads", " 2"}, "--threads: ' 2' is not a whole number in [1, 64]"},
      {{"in", "--threads", "99999999999999999999"}, "--threads: '99999999999999999999' is not"},
      {{"in", "--scale", "0"}, "--scale: '0' is not a finite number > 0"},
      {{"in", "--scale", "inf"}, "--scale: 'inf' is not a finite number > 0"},
      {{"in", "--scale", "nan"}, "--scale: 'nan' is not a finite number > 0"},
      {{"in", "--scale", "1m"}, "--scale: '1m' is not a finite number > 0"},
      {{"in", "--scale", ""}, "--scale: '' is not a finite number > 0"},
      {{}, "missing IN"},
      {{"in", "extra"}, "unexpected argument 'extra'"},
  };
  for (const auto& [argv, expected] : cases) {
    Args args;
    std::string error;
    EXPECT_EQ(Parse(argv, &args, &error), Status::kError) << expected;
    EXPECT_EQ(error.rfind(expected, 0), 0u) << "got '" << error << "', expected '" << expected
                                            << "'";
  }
}

TEST(CommandLineTest, DoubleDashEndsOptions) {
  Args args;
  std::string error;
  ASSERT_EQ(Parse({"--quiet", "--", "--in"}, &args, &error), Status::kOk) << error;
  EXPECT_EQ(args.in, "--in");
  EXPECT_EQ(Parse({"-"}, &args, &error), Status::kOk) << "'-' alone is an argument";
  EXPECT_EQ(args.in, "-");
}

TEST(CommandLineTest, RequiredOptionsAndGiven) {
  std::string gt, est = "est.tum";
  CommandLine command_line("prog ate", kUsage);
  command_line.AddString("--gt", &gt, CommandLine::Required::kYes);
  command_line.AddString("--est", &est);
  std::string error;
  EXPECT_EQ(command_line.Parse({"--est", "x.tum"}, &error), Status::kError);
  EXPECT_EQ(error, "missing required option --gt");
  EXPECT_TRUE(command_line.Given("--est"));
  EXPECT_FALSE(command_line.Given("--gt"));
}

TEST(CommandLineTest, ListsChoicesAndInt64) {
  std::vector<double> sizes = {1, 5, 20};
  std::vector<double> intrinsics;
  std::vector<std::string> images, tags;
  std::string unit = "m";
  int64_t seed = 1;
  bool rgbd = true;
  CommandLine command_line("prog", kUsage);
  command_line.AddDoubleList("--sizes", &sizes, {0.0, 100.0, true});
  command_line.AddDoubleList("--intrinsics", &intrinsics, {}, 4);
  command_line.AddStringList("--tag", &tags);
  command_line.AddChoice("--unit", &unit, {"m", "s"});
  command_line.AddInt64("--seed", &seed, 0, std::numeric_limits<int64_t>::max());
  command_line.AddFlag("--no-rgbd", &rgbd, false);
  command_line.AddPositionalList("IMAGE...", &images, 1);
  std::string error;
  ASSERT_EQ(command_line.Parse({"a.png", "--sizes", "0.5,2", "--tag", "x", "b.png", "--tag", "y",
                                "--unit", "s", "--seed", "12345678901", "--no-rgbd",
                                "--intrinsics", "525,525,319.5,-1"},
                               &error),
            Status::kOk)
      << error;
  EXPECT_EQ(sizes, (std::vector<double>{0.5, 2}));
  EXPECT_EQ(intrinsics, (std::vector<double>{525, 525, 319.5, -1}));
  EXPECT_EQ(images, (std::vector<std::string>{"a.png", "b.png"}));
  EXPECT_EQ(tags, (std::vector<std::string>{"x", "y"}));
  EXPECT_EQ(unit, "s");
  EXPECT_EQ(seed, 12345678901);
  EXPECT_FALSE(rgbd);
}

TEST(CommandLineTest, BadListsChoicesAndMissingPositionalList) {
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"a", "--sizes", "1,0"}, "--sizes: '0' is not a finite number in (0, 100]"},
      {{"a", "--sizes", "1,"}, "--sizes: '1,' is not a list of comma-separated numbers"},
      {{"a", "--intrinsics", "1,2,3"}, "--intrinsics: '1,2,3' is not 4 comma-separated numbers"},
      {{"a", "--unit", "km"}, "--unit: 'km' is not one of m, s"},
      {{"a", "--seed", "-1"}, "--seed: '-1' is not a whole number >= 0"},
      {{}, "missing IMAGE..."},
  };
  for (const auto& [argv, expected] : cases) {
    std::vector<double> sizes, intrinsics;
    std::vector<std::string> images;
    std::string unit;
    int64_t seed = 0;
    CommandLine command_line("prog", kUsage);
    command_line.AddDoubleList("--sizes", &sizes, {0.0, 100.0, true});
    command_line.AddDoubleList("--intrinsics", &intrinsics, {}, 4);
    command_line.AddChoice("--unit", &unit, {"m", "s"});
    command_line.AddInt64("--seed", &seed, 0, std::numeric_limits<int64_t>::max());
    command_line.AddPositionalList("IMAGE...", &images, 1);
    std::string error;
    EXPECT_EQ(command_line.Parse(argv, &error), Status::kError) << expected;
    EXPECT_EQ(error, expected);
  }
}

TEST(CommandLineTest, ParseOrExitCodePrintsUsageAndReturnsTheExitCode) {
  const char* help[] = {"prog", "--help"};
  const char* bad[] = {"prog", "in", "--threads", "0"};
  const char* good[] = {"prog", "in"};
  for (const auto& [argv, argc, expected] :
       {std::make_tuple(help, 2, std::optional<int>(kExitSuccess)),
        std::make_tuple(bad, 4, std::optional<int>(kExitUsage)),
        std::make_tuple(good, 2, std::optional<int>())}) {
    Args args;
    CommandLine command_line("prog", kUsage);
    Declare(&command_line, &args);
    std::ostringstream out, err;
    EXPECT_EQ(command_line.ParseOrExitCode(argc, argv, 1, out, err), expected);
    if (expected == kExitSuccess) {
      EXPECT_EQ(out.str(), kUsage);
      EXPECT_EQ(err.str(), "");
    } else if (expected == kExitUsage) {
      EXPECT_EQ(out.str(), "");
      EXPECT_EQ(err.str(), std::string("prog: --threads: '0' is not a whole number in [1, 64]\n") +
                               kUsage);
    } else {
      EXPECT_EQ(out.str() + err.str(), "");
    }
  }
}

TEST(CommandLineTest, RunSubcommandDispatchesOnTheFirstArgument) {
  int calls = 0;
  const std::vector<Subcommand> commands = {
      {"ate", [&calls](int argc, char** argv) {
         ++calls;
         return argc == 3 && std::string(argv[2]) == "x" ? 7 : -1;
       }}};
  const auto run = [&](std::vector<std::string> args, std::string* out, std::string* err) {
    std::vector<char*> argv;
    for (std::string& arg : args) argv.push_back(arg.data());
    std::ostringstream out_stream, err_stream;
    const int code = RunSubcommand("prog", kUsage, commands, static_cast<int>(argv.size()),
                                   argv.data(), out_stream, err_stream);
    *out = out_stream.str();
    *err = err_stream.str();
    return code;
  };
  std::string out, err;
  EXPECT_EQ(run({"prog", "ate", "x"}, &out, &err), 7);
  EXPECT_EQ(calls, 1);
  EXPECT_EQ(run({"prog", "--help"}, &out, &err), kExitSuccess);
  EXPECT_EQ(out, kUsage);
  EXPECT_EQ(run({"prog"}, &out, &err), kExitUsage);
  EXPECT_EQ(err, std::string("prog: missing command\n") + kUsage);
  EXPECT_EQ(run({"prog", "rpe"}, &out, &err), kExitUsage);
  EXPECT_EQ(err, std::string("prog: unknown command 'rpe'\n") + kUsage);
  EXPECT_EQ(calls, 1);
}

// fusemap_offline's and fusemapd's lines (still parsed by hand): required paths, flags that
// switch something off, a repeated --threads N in 1..64 (the last wins), any finite offset.
TEST(CommandLineTest, ExpressesTheOfflineRunnersCommandLine) {
  std::string log, config, out, relations;
  bool loop_closure = true, quiet = false;
  int threads = 1;
  double relations_time_offset_s = 0.0;
  CommandLine command_line("fusemap_offline", kUsage);
  command_line.AddString("--log", &log, CommandLine::Required::kYes);
  command_line.AddString("--config", &config, CommandLine::Required::kYes);
  command_line.AddString("--out", &out, CommandLine::Required::kYes);
  command_line.AddFlag("--no-loop-closure", &loop_closure, false);
  command_line.AddFlag("--quiet", &quiet);
  command_line.AddInt("--threads", &threads, 1, 64);
  command_line.AddString("--relations", &relations);
  command_line.AddDouble("--relations-time-offset", &relations_time_offset_s);
  std::string error;
  ASSERT_EQ(command_line.Parse({"--log", "a.lcm", "--config", "c.yaml", "--out", "o", "--threads",
                                "4", "--no-loop-closure", "--relations-time-offset", "-1e9",
                                "--threads", "2"},
                               &error),
            Status::kOk)
      << error;
  EXPECT_EQ(threads, 2);
  EXPECT_FALSE(loop_closure);
  EXPECT_FALSE(quiet);
  EXPECT_EQ(relations_time_offset_s, -1e9);
  EXPECT_EQ(out, "o");
}

TEST(CommandLineTest, UsageErrorPrintsProgramMessageAndUsage) {
  CommandLine command_line("fusemap_x", kUsage);
  std::ostringstream err;
  EXPECT_EQ(command_line.UsageError("OUTPUT is the same file as INPUT", err), kExitUsage);
  EXPECT_EQ(err.str(), std::string("fusemap_x: OUTPUT is the same file as INPUT\n") + kUsage);
}

}  // namespace
}  // namespace common
}  // namespace fusemap
