// See report_format.hpp.
#include "report_format.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "horopter/core/error.hpp"

namespace horopter::cli {

std::string interval(const eval::RatioEstimate& e) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.1f [%.1f,%.1f]", e.value, e.low, e.high);
  return buf;
}

std::string reportability(eval::SeedUse use, int trials) {
  if (use != eval::SeedUse::TrialEvaluation)
    return "tuning seeds: figures for diagnosis and tuning, not for reporting "
           "(docs/evaluation.md)";
  if (trials < eval::kMinReportedTrials)
    return "evaluation seeds, but fewer than " + std::to_string(eval::kMinReportedTrials) +
           " trials: not a reportable figure (docs/evaluation.md)";
  return "evaluation seeds, " + std::to_string(trials) +
         " trials: reportable once, if this block was never run before (docs/evaluation.md)";
}

void writeJsonLine(const std::string& text) {
  errno = 0;
  if (std::fwrite(text.data(), 1, text.size(), stdout) != text.size() ||
      std::fputc('\n', stdout) == EOF || std::fflush(stdout) != 0)
    throw Error(std::string("cannot write the JSON report to standard output") +
                (errno ? std::string(": ") + std::strerror(errno) : std::string()));
}

}  // namespace horopter::cli
