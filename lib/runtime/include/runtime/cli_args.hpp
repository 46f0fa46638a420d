// A small, strict command-line parser: declared options only, values checked,
// unknown options rejected with UsageError. Commands parse into a Settings
// struct in setup() and do the work in run().
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace globe {

class CliArgs {
 public:
  CliArgs(std::string program, std::string usage_line)
      : program_(std::move(program)), usage_(std::move(usage_line)) {}

  // Declares an option taking a value (--name VALUE or --name=VALUE).
  void option(const std::string& names, const std::string& value_name, const std::string& help,
              std::function<void(const std::string&)> on_value);
  // Declares a flag without a value.
  void flag(const std::string& names, const std::string& help, std::function<void()> on_flag);
  // Parses argv (excluding the program and command names); returns the
  // positional arguments. Throws UsageError. Returns nullopt after --help or
  // --version.
  std::optional<std::vector<std::string>> parse(const std::vector<std::string>& args);
  // Text printed after the options by --help (e.g. window keys).
  void epilogue(std::string text) { epilogue_ = std::move(text); }
  std::string help() const;
  // parse(), printing the help (or "PROGRAM VERSION") on stdout for --help
  // (--version), then nullopt, and
  // requiring between min and max positional `what` arguments.
  std::optional<std::vector<std::string>> parse_command(const std::vector<std::string>& args,
                                                        size_t min, size_t max,
                                                        const std::string& what);

  // Value parsers that throw UsageError naming the option.
  // An output path as the user meant it: without trailing slashes, so "out/"
  // names the folder (or file) "out" and temporary names beside it
  // ("out.tmp") do not land inside it.
  static std::string to_output_path(const std::string& v);
  static int to_int(const std::string& option, const std::string& v, int lo, int hi);
  static double to_double(const std::string& option, const std::string& v);
  static std::vector<double> to_doubles(const std::string& option, const std::string& v, size_t n);
  // Comma-separated names (empty items dropped): at least one, and exactly
  // `n` unless n is 0.
  static std::vector<std::string> to_names(const std::string& option, const std::string& v,
                                           size_t n = 0);
  // The command line recorded in package metadata: `prefix` and the
  // arguments without options that cannot change the output (-j/--threads,
  // -q/--quiet, --progress, --force, --memory-mb), so packages built with any
  // -j or memory budget match.
  static std::string reproducible_command_line(const std::string& prefix,
                                               const std::vector<std::string>& args);

 private:
  struct Opt {
    std::vector<std::string> names;
    std::string value_name, help;
    std::function<void(const std::string&)> on_value;
    std::function<void()> on_flag;
  };
  const Opt* find(const std::string& name) const;
  std::string program_, usage_, epilogue_;
  bool version_asked_ = false;
  std::vector<Opt> opts_;
};

}  // namespace globe
