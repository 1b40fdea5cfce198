// What the evaluation commands print beside their figures: intervals, the
// seed range's standing under the protocol (docs/evaluation.md), and JSON
// written with its errors checked.
#pragma once

#include <string>

#include "eval/bootstrap.hpp"
#include "eval/seed_ranges.hpp"

namespace horopter::cli {

// "12.3 [8.1,16.0]": a percentage and its interval, one decimal.
std::string interval(const eval::RatioEstimate& percent);

// One line: whether figures from these seeds may be reported, and why not.
std::string reportability(eval::SeedUse use, int trials);

// Writes `text` and a newline to standard output; throws horopter::Error
// when it cannot (a closed pipe, a full disk).
void writeJsonLine(const std::string& text);

}  // namespace horopter::cli
