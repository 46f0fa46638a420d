// Command-line parsing (see cli_args.hpp).
#include "runtime/cli_args.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "runtime/errors.hpp"

namespace globe {

void CliArgs::option(const std::string& names, const std::string& value_name,
                     const std::string& help, std::function<void(const std::string&)> on_value) {
  Opt o;
  std::istringstream in(names);
  for (std::string n; std::getline(in, n, ',');)
    o.names.push_back(n);
  o.value_name = value_name;
  o.help = help;
  o.on_value = std::move(on_value);
  opts_.push_back(std::move(o));
}

void CliArgs::flag(const std::string& names, const std::string& help,
                   std::function<void()> on_flag) {
  Opt o;
  std::istringstream in(names);
  for (std::string n; std::getline(in, n, ',');)
    o.names.push_back(n);
  o.help = help;
  o.on_flag = std::move(on_flag);
  opts_.push_back(std::move(o));
}

const CliArgs::Opt* CliArgs::find(const std::string& name) const {
  for (const auto& o : opts_)
    for (const auto& n : o.names)
      if (n == name) return &o;
  return nullptr;
}

std::optional<std::vector<std::string>> CliArgs::parse(const std::vector<std::string>& args) {
  std::vector<std::string> positional;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "-h" || a == "--help") return std::nullopt;
    if (a == "--version") {
      version_asked_ = true;
      return std::nullopt;
    }
    if (a == "--") {
      positional.insert(positional.end(), args.begin() + i + 1, args.end());
      break;
    }
    if (a.size() < 2 || a[0] != '-' || (a[1] >= '0' && a[1] <= '9')) {
      positional.push_back(a);
      continue;
    }
    std::string name = a, value;
    bool has_value = false;
    if (auto eq = a.find('='); eq != std::string::npos && a.rfind("--", 0) == 0) {
      name = a.substr(0, eq);
      value = a.substr(eq + 1);
      has_value = true;
    }
    // Short options may carry their value attached: -j2.
    if (!has_value && a[1] != '-' && a.size() > 2 && !find(a)) {
      if (const Opt* shortopt = find(a.substr(0, 2)); shortopt && shortopt->on_value) {
        name = a.substr(0, 2);
        value = a.substr(2);
        has_value = true;
      }
    }
    const Opt* o = find(name);
    if (!o) throw UsageError("unknown option " + name + " (see " + program_ + " --help)");
    if (o->on_flag) {
      if (has_value) throw UsageError(name + " takes no value");
      o->on_flag();
      continue;
    }
    if (!has_value) {
      if (i + 1 >= args.size()) throw UsageError(name + " needs a value (" + o->value_name + ")");
      value = args[++i];
    }
    o->on_value(value);
  }
  return positional;
}

std::optional<std::vector<std::string>> CliArgs::parse_command(const std::vector<std::string>& args,
                                                               size_t min, size_t max,
                                                               const std::string& what) {
  auto positional = parse(args);
  if (!positional) {
    if (version_asked_)
      std::printf("%s %s\n", program_.substr(0, program_.find(' ')).c_str(), GLOBE_VERSION);
    else
      std::fputs(help().c_str(), stdout);
    return std::nullopt;
  }
  if (positional->size() < min)
    throw UsageError(min == max ? "expected " + std::to_string(min) + " " + what
                                : "no " + what + " given");
  if (positional->size() > max)
    throw UsageError("expected at most " + std::to_string(max) + " " + what);
  return positional;
}

std::string CliArgs::help() const {
  std::ostringstream out;
  out << "usage: " << usage_ << "\n\noptions:\n";
  for (const auto& o : opts_) {
    std::string left = "  ";
    for (size_t i = 0; i < o.names.size(); ++i)
      left += (i ? ", " : "") + o.names[i];
    if (!o.value_name.empty()) left += " " + o.value_name;
    if (left.size() < 30)
      left.resize(30, ' ');
    else
      left += "\n" + std::string(30, ' ');
    out << left << o.help << "\n";
  }
  out << "  -h, --help                  show this help\n";
  out << "  --version                   print the program's version\n";
  if (!epilogue_.empty()) out << "\n" << epilogue_;
  return out.str();
}

std::string CliArgs::to_output_path(const std::string& v) {
  std::string path = v;
  while (path.size() > 1 && path.back() == '/')
    path.pop_back();
  return path;
}

int CliArgs::to_int(const std::string& option, const std::string& v, int lo, int hi) {
  size_t used = 0;
  long long x = 0;
  try {
    x = std::stoll(v, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != v.size() || v.empty()) throw UsageError(option + ": '" + v + "' is not an integer");
  if (x < lo || x > hi)
    throw UsageError(option + ": " + v + " is out of range (" + std::to_string(lo) + ".." +
                     std::to_string(hi) + ")");
  return static_cast<int>(x);
}

double CliArgs::to_double(const std::string& option, const std::string& v) {
  size_t used = 0;
  double x = 0;
  try {
    x = std::stod(v, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != v.size() || v.empty() || !std::isfinite(x))
    throw UsageError(option + ": '" + v + "' is not a number");
  return x;
}

std::vector<double> CliArgs::to_doubles(const std::string& option, const std::string& v, size_t n) {
  std::vector<double> out;
  std::istringstream in(v);
  for (std::string part; std::getline(in, part, ',');)
    out.push_back(to_double(option, part));
  if (out.size() != n)
    throw UsageError(option + ": expected " + std::to_string(n) +
                     " comma-separated numbers, got '" + v + "'");
  return out;
}

std::vector<std::string> CliArgs::to_names(const std::string& option, const std::string& v,
                                           size_t n) {
  std::vector<std::string> out;
  std::istringstream in(v);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) out.push_back(item);
  if (out.empty()) throw UsageError(option + ": give one or more names separated by commas");
  if (n && out.size() != n)
    throw UsageError(option + ": expected " + std::to_string(n) + " comma-separated names, got '" +
                     v + "'");
  return out;
}

}  // namespace globe

namespace globe {

std::string CliArgs::reproducible_command_line(const std::string& prefix,
                                               const std::vector<std::string>& args) {
  std::string out = prefix;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "-j" || a == "--threads" || a == "--progress" || a == "--memory-mb" ||
        a == "--flow-chunk") {
      ++i;
      continue;
    }
    if (a == "-q" || a == "--quiet" || a == "--force" || a == "--resume" ||
        a.rfind("--threads=", 0) == 0 || a.rfind("--progress=", 0) == 0 ||
        a.rfind("--memory-mb=", 0) == 0 || a.rfind("--flow-chunk=", 0) == 0 ||
        (a.size() > 2 && a.rfind("-j", 0) == 0))
      continue;
    out += " " + a;
  }
  return out;
}

}  // namespace globe
