// Strict number parsing and the range message; see horopter/core/option_table.hpp.
#include "horopter/core/option_table.hpp"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace horopter {

namespace {

std::string rangeText(long long min, long long max) {
  return std::to_string(min) + ".." + std::to_string(max);
}

std::string numberText(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

}  // namespace

long long parseInteger(const std::string& text, const std::string& option, long long min,
                       long long max) {
  const std::string expected =
      option + " needs an integer within " + rangeText(min, max) + ", got '" + text + "'";
  // strtoll skips leading blanks and takes a sign; neither a blank nor a '+'
  // is part of a number on a command line or in a file.
  if (text.empty() || std::isspace(static_cast<unsigned char>(text.front())) || text[0] == '+')
    throw Error(expected);
  errno = 0;
  char* end = nullptr;
  const long long v = std::strtoll(text.c_str(), &end, 10);
  if (errno == ERANGE || end != text.c_str() + text.size() || v < min || v > max)
    throw Error(expected);
  return v;
}

double parseNumber(const std::string& text, const std::string& option, double min, double max) {
  // A range that admits every finite double is not worth printing.
  const bool anyFinite = min <= -1e300 && max >= 1e300;
  const std::string expected =
      option +
      (anyFinite ? " needs a finite number"
                 : " needs a number within " + numberText(min) + ".." + numberText(max)) +
      ", got '" + text + "'";
  if (text.empty() || std::isspace(static_cast<unsigned char>(text.front())) || text[0] == '+')
    throw Error(expected);
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  // strtod reads "nan", "inf" and hexadecimal floats: none is a parameter.
  const bool hex = text.find_first_of("xX") != std::string::npos;
  if (errno == ERANGE || end != text.c_str() + text.size() || hex || !std::isfinite(v) || v < min ||
      v > max)
    throw Error(expected);
  return v;
}

std::string rangeMessage(const std::string& name, const std::string& unit, long long min,
                         long long max, long long value) {
  return name + " must be within " + rangeText(min, max) + (unit.empty() ? "" : " " + unit) +
         ", got " + std::to_string(value);
}

std::string numberRangeMessage(const std::string& name, const std::string& unit, double min,
                               double max, double value) {
  return name + " must be within " + numberText(min) + ".." + numberText(max) +
         (unit.empty() ? "" : " " + unit) + ", got " + numberText(value);
}

}  // namespace horopter
