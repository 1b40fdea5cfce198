// Options declared once. A parameter struct lists its options in a table:
// name (the member's name, which is also the Python keyword and the JSON
// key), command-line flag, unit, range and one line of help. Validation, the
// CLI's flags and help, the Python keywords and the JSON all read the table,
// so none of them restates a range or a default (the default is the struct's
// own member initialiser).
#pragma once

#include "horopter/core/export.hpp"

#include <cmath>
#include <span>
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

// An option of a tuning struct (the detector's, the tracker's, the
// election's, head control's): an int or double member, a range in the
// member's unit. Integer members take whole numbers only.
template <class Params>
struct NumberOption {
  const char* name;                  // the member's name: Python keyword, JSON key
  const char* flag;                  // the command-line flag
  const char* unit;                  // "s", "px", "" (a count or a fraction)...
  double min, max;                   // the allowed range, inclusive
  const char* help;                  // what it does; what 0 means where it switches it off
  int Params::*intMember = nullptr;  // one of the two is set
  double Params::*numberMember = nullptr;

  constexpr NumberOption(const char* name_, const char* flag_, const char* unit_, double min_,
                         double max_, const char* help_, int Params::*member)
      : name(name_),
        flag(flag_),
        unit(unit_),
        min(min_),
        max(max_),
        help(help_),
        intMember(member) {}
  constexpr NumberOption(const char* name_, const char* flag_, const char* unit_, double min_,
                         double max_, const char* help_, double Params::*member)
      : name(name_),
        flag(flag_),
        unit(unit_),
        min(min_),
        max(max_),
        help(help_),
        numberMember(member) {}

  bool integer() const { return intMember != nullptr; }
// GCC 12 inlines both branches of get() and, for a struct without int
// members, warns that the null int member (offset -1) reads uninitialised
// bytes: it cannot see that branch is never taken.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
  double get(const Params& p) const {
    return integer() ? p.*intMember : p.*numberMember;
  }
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
  void set(Params& p, double v) const {
    if (integer())
      p.*intMember = static_cast<int>(v);
    else
      p.*numberMember = v;
  }
};

// "<name> must be within <min>..<max> <unit>, got <value>", for any number.
HOROPTER_API std::string numberRangeMessage(const std::string& name, const std::string& unit,
                                            double min, double max, double value);

// Throws horopter::Error (numberRangeMessage) for the first option of the
// table that is out of range (NaN included).
template <class Params>
void checkRanges(std::span<const NumberOption<Params>> table, const Params& p) {
  for (const NumberOption<Params>& o : table) {
    const double v = o.get(p);
    if (!(v >= o.min && v <= o.max))
      throw Error(numberRangeMessage(o.name, o.unit, o.min, o.max, v));
  }
}

}  // namespace horopter
