// Options declared once. A parameter struct lists its options in a table:
// name (the member's name, which is also the Python keyword and the JSON
// key), command-line flag, unit, range and one line of help. Validation, the
// CLI's flags and help, the Python keywords and the JSON all read the table,
// so none of them restates a range or a default (the default is the struct's
// own member initialiser).
#pragma once

#include "horopter/core/export.hpp"

#include <string>

#include "horopter/core/error.hpp"

namespace horopter {

template <class Params>
struct IntOption {
  const char* name;  // the member's name: Python keyword, JSON key
  const char* flag;  // the command-line flag
  const char* unit;  // "px", "1/16 px", "%", or "" (a count)
  int min, max;      // the allowed range, inclusive (rules across options: validate())
  const char* help;  // what it does; what 0 or -1 means where they switch it off
  int Params::*member;
};

// Strict parsing, for every front end: the whole text must be a number in
// [min, max]; "2junk", "abc", "", "nan", "inf" and out-of-range values throw
// horopter::Error naming `option` and the range.
HOROPTER_API long long parseInteger(const std::string& text, const std::string& option,
                                    long long min, long long max);
HOROPTER_API double parseNumber(const std::string& text, const std::string& option, double min,
                                double max);

// "<name> must be within <min>..<max> <unit>, got <value>".
HOROPTER_API std::string rangeMessage(const std::string& name, const std::string& unit,
                                      long long min, long long max, long long value);

// Throws horopter::Error (rangeMessage) where p's option is out of range.
template <class Params>
void checkRange(const IntOption<Params>& o, const Params& p) {
  const int v = p.*o.member;
  if (v < o.min || v > o.max) throw Error(rangeMessage(o.name, o.unit, o.min, o.max, v));
}

}  // namespace horopter
