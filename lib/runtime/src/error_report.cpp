// Errors -> messages and exit codes (see error_report.hpp).
#include "runtime/error_report.hpp"

#include <cstdio>
#include <exception>

#include "runtime/errors.hpp"
#include "tileformat/error.hpp"

namespace globe {

int run_reporting_errors(const std::string& program, const std::string& usage_prefix,
                         const std::string& usage_suffix, const std::function<int()>& body) {
  auto report = [&](const std::exception& e, int code) {
    std::fprintf(stderr, "%s: %s\n", program.c_str(), e.what());
    return code;
  };
  try {
    return body();
  } catch (const UsageError& e) {
    std::fprintf(stderr, "%s: %s%s\n", usage_prefix.c_str(), e.what(), usage_suffix.c_str());
    return kExitUsage;
  } catch (const OutputError& e) {
    return report(e, kExitOutputError);
  } catch (const InputError& e) {
    return report(e, kExitDataError);
  } catch (const tileformat::FormatError& e) {
    return report(e, kExitDataError);
  } catch (const tileformat::PackageError& e) {
    return report(e, kExitDataError);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: internal error: %s\n", program.c_str(), e.what());
    return kExitInternal;
  }
}

}  // namespace globe
