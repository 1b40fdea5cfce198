#include "command_options.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "horopter/core/option_table.hpp"

namespace horopter::cli {

namespace {

bool takesValue(const CommandOption& o) {
  return o.kind != OptionKind::Switch && o.kind != OptionKind::Heading;
}

// A range that admits every finite number is not worth printing.
bool unbounded(const CommandOption& o) {
  return o.min <= -1e300 && o.max >= 1e300;
}

long long integerMin(const CommandOption& o) {
  return static_cast<long long>(std::ceil(o.min));
}
long long integerMax(const CommandOption& o) {
  return static_cast<long long>(std::floor(o.max));
}

std::vector<std::string> choiceList(const CommandOption& o) {
  std::vector<std::string> out;
  std::stringstream in(o.choices);
  std::string item;
  while (std::getline(in, item, ','))
    out.push_back(item);
  return out;
}

// "a, b or c".
std::string choiceText(const CommandOption& o) {
  const std::vector<std::string> list = choiceList(o);
  std::string out;
  for (std::size_t i = 0; i < list.size(); ++i)
    out += (i == 0 ? "" : i + 1 == list.size() ? " or " : ", ") + list[i];
  return out;
}

// Throws UsageError when `text` is not a value of o (its kind, range, choices).
void check(const CommandOption& o, const std::string& text) {
  asUsageError([&] {
    if (o.kind == OptionKind::Integer)
      parseInteger(text, o.flag, integerMin(o), integerMax(o));
    else if (o.kind == OptionKind::Number)
      parseNumber(text, o.flag, o.min, o.max);
  });
  if (o.kind != OptionKind::Choice) return;
  for (const std::string& c : choiceList(o))
    if (c == text) return;
  throw UsageError(std::string(o.flag) + " takes " + choiceText(o) + ", got '" + text + "'");
}

const char* kindName(OptionKind k) {
  switch (k) {
    case OptionKind::Switch:
      return "a switch";
    case OptionKind::Integer:
      return "an integer";
    case OptionKind::Number:
      return "a number";
    case OptionKind::Text:
      return "a text";
    case OptionKind::Choice:
      return "a choice";
    case OptionKind::Heading:
      return "a heading";
  }
  return "?";
}

// A table's own mistakes (a default outside its range or choices, a flag
// declared twice) are programming errors: every run of the command finds
// them, and so does the test that runs every command's parser
// (cli.help_lists_every_flag).
void checkTable(std::span<const CommandOption> table) {
  for (std::size_t i = 0; i < table.size(); ++i) {
    const CommandOption& o = table[i];
    if (o.kind == OptionKind::Heading) continue;
    for (std::size_t j = 0; j < i; ++j)
      for (const char* name : {o.flag, o.alias})
        if (*name && table[j].kind != OptionKind::Heading &&
            (std::string(name) == table[j].flag || std::string(name) == table[j].alias))
          throw std::logic_error(std::string("option ") + name + " is declared twice");
    if (o.kind == OptionKind::Choice && !*o.choices)
      throw std::logic_error(std::string("option ") + o.flag + " has no choices");
    if (*o.fallback && o.fallbackOf)
      throw std::logic_error(std::string("option ") + o.flag + " has two defaults");
    const std::string fallback = fallbackText(o);
    if (fallback.empty() || !takesValue(o)) continue;
    try {
      check(o, fallback);
    } catch (const UsageError& e) {
      throw std::logic_error(std::string("the default of ") + o.flag +
                             " is not one of its values: " + e.what());
    }
  }
}

}  // namespace

CommandOptions::CommandOptions(Args& args, std::span<const CommandOption> table) : table_(table) {
  checkTable(table);
  for (const CommandOption& o : table) {
    if (o.kind == OptionKind::Heading) continue;
    int seen = 0;
    for (const char* name : {o.flag, o.alias}) {
      if (!*name) continue;
      if (!takesValue(o)) {
        while (args.flag(name))
          ++seen;
        continue;
      }
      while (const std::optional<std::string> v = args.value(name)) {
        if (seen++ == 0) {
          check(o, *v);
          values_.emplace_back(o.flag, *v);
        }
      }
    }
    if (seen > 1) throw UsageError(std::string(o.flag) + " is given more than once");
    if (seen == 1 && !takesValue(o)) switches_.insert(o.flag);
  }
}

const CommandOption& CommandOptions::entry(const std::string& flag,
                                           std::initializer_list<OptionKind> kinds) const {
  for (const CommandOption& o : table_) {
    if (o.kind == OptionKind::Heading || flag != o.flag) continue;
    for (OptionKind k : kinds)
      if (k == o.kind) return o;
    throw std::logic_error("option " + flag + " is " + kindName(o.kind) + ", read as another kind");
  }
  throw std::logic_error("option " + flag + " is read but not declared in the command's table");
}

std::optional<std::string> CommandOptions::raw(const CommandOption& o) const {
  for (const auto& [flag, text] : values_)
    if (flag == o.flag) return text;
  if (const std::string fallback = fallbackText(o); !fallback.empty()) return fallback;
  return std::nullopt;
}

bool CommandOptions::given(const std::string& flag) const {
  const CommandOption& o = entry(flag, {OptionKind::Switch, OptionKind::Integer, OptionKind::Number,
                                        OptionKind::Text, OptionKind::Choice});
  if (!takesValue(o)) return switches_.count(o.flag) > 0;
  for (const auto& [f, text] : values_)
    if (f == o.flag) return true;
  return false;
}

bool CommandOptions::on(const std::string& flag) const {
  return switches_.count(entry(flag, {OptionKind::Switch}).flag) > 0;
}

std::optional<long long> CommandOptions::optionalInteger(const std::string& flag) const {
  const CommandOption& o = entry(flag, {OptionKind::Integer});
  const auto v = raw(o);
  if (!v) return std::nullopt;
  return parseInteger(*v, o.flag, integerMin(o), integerMax(o));
}

std::optional<double> CommandOptions::optionalNumber(const std::string& flag) const {
  const CommandOption& o = entry(flag, {OptionKind::Number});
  const auto v = raw(o);
  if (!v) return std::nullopt;
  return parseNumber(*v, o.flag, o.min, o.max);
}

long long CommandOptions::integer(const std::string& flag) const {
  const auto v = optionalInteger(flag);
  if (!v)
    throw std::logic_error("option " + flag + " has no default: read it with optionalInteger");
  return *v;
}

double CommandOptions::number(const std::string& flag) const {
  const auto v = optionalNumber(flag);
  if (!v) throw std::logic_error("option " + flag + " has no default: read it with optionalNumber");
  return *v;
}

std::optional<std::string> CommandOptions::optionalText(const std::string& flag) const {
  return raw(entry(flag, {OptionKind::Text, OptionKind::Choice}));
}

std::string CommandOptions::text(const std::string& flag) const {
  return optionalText(flag).value_or("");
}

std::string commandOptionsHelp(std::span<const CommandOption> table) {
  std::string out;
  for (const CommandOption& o : table) {
    if (o.kind == OptionKind::Heading) {
      out += std::string(o.flag) + ":\n";
      continue;
    }
    std::ostringstream name, text;
    name << (*o.alias ? std::string(o.alias) + ", " : std::string()) << o.flag
         << (takesValue(o) ? std::string(" ") + o.value : std::string());
    text << o.help;
    if (o.kind == OptionKind::Integer)
      text << "; " << integerMin(o) << ".." << integerMax(o);
    else if (o.kind == OptionKind::Number && !unbounded(o))
      text << "; " << o.min << ".." << o.max;
    else if (o.kind == OptionKind::Choice)
      text << "; " << choiceText(o);
    if (*o.unit) text << " " << o.unit;
    if (const std::string fallback = fallbackText(o); !fallback.empty())
      text << " (default " << fallback << ")";
    out += helpEntry(name.str(), text.str());
  }
  return out;
}

std::string defaultText(double value) {
  std::ostringstream text;
  text << value;  // the shortest form, up to 6 significant digits
  return text.str();
}

std::string fallbackText(const CommandOption& o) {
  return o.fallbackOf ? o.fallbackOf() : std::string(o.fallback);
}

std::vector<std::string> commandOptionFlags(std::span<const CommandOption> table) {
  std::vector<std::string> out;
  for (const CommandOption& o : table) {
    if (o.kind == OptionKind::Heading) continue;
    out.emplace_back(o.flag);
    if (*o.alias) out.emplace_back(o.alias);
  }
  return out;
}

}  // namespace horopter::cli
