// The movement model's versioned text file; the format is described in
// include/horopter/movement/movement_classifier.hpp.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "file_output.hpp"
#include "horopter/core/error.hpp"
#include "horopter/movement/movement_classifier.hpp"

namespace horopter {

namespace {

std::string formatDouble(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// Reads the file's records in order, each checked against what must come.
class Reader {
 public:
  Reader(const std::string& text, const std::string& source) : in_(text), source_(source) {}

  // The next non-empty, non-comment line split into words.
  std::vector<std::string> next(const std::string& expected) {
    std::string line;
    while (std::getline(in_, line)) {
      ++lineNo_;
      if (!line.empty() && line.back() == '\r') line.pop_back();
      if (line.empty() || line[0] == '#') continue;
      std::istringstream words(line);
      std::vector<std::string> out;
      for (std::string w; words >> w;)
        out.push_back(w);
      if (out.empty()) continue;
      if (out[0] != expected) fail("expected a '" + expected + "' record, found '" + out[0] + "'");
      return out;
    }
    fail("the file ends before the '" + expected + "' record (truncated?)");
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw Error("movement model '" + source_ + "' line " + std::to_string(lineNo_) + ": " + what +
                "; write a new one with horopter train");
  }
  double number(const std::string& word) const {
    std::size_t used = 0;
    double v = 0;
    try {
      v = std::stod(word, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != word.size()) fail("'" + word + "' is not a number");
    return v;
  }
  std::int64_t count(const std::string& word) const {
    std::size_t used = 0;
    long long v = -1;
    try {
      v = std::stoll(word, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != word.size() || v < 0) fail("'" + word + "' is not a count (an integer >= 0)");
    return v;
  }
  void expectSize(const std::vector<std::string>& rec, std::size_t n) const {
    if (rec.size() != n)
      fail("'" + rec[0] + "' has " + std::to_string(rec.size() - 1) + " values, expected " +
           std::to_string(n - 1));
  }
  int lineNo() const { return lineNo_; }
  // Only blank and comment lines may follow the last record.
  void expectEnd() {
    std::string line;
    while (std::getline(in_, line)) {
      ++lineNo_;
      if (!line.empty() && line.back() == '\r') line.pop_back();
      if (line.find_first_not_of(" \t") == std::string::npos || line[0] == '#') continue;
      fail("text after 'end': '" + line.substr(0, 40) + "'");
    }
  }

 private:
  std::istringstream in_;
  std::string source_;
  int lineNo_ = 0;
};

}  // namespace

std::string MovementModel::serialize() const {
  std::ostringstream out;
  out << kMagic << ' ' << kFormatVersion << '\n';
  out << "# LMA symbol counts per movement; see "
         "include/horopter/movement/movement_classifier.hpp\n";
  out << "params " << formatDouble(params_.stay) << ' ' << formatDouble(params_.evidenceWeight)
      << ' ' << formatDouble(params_.decisionThreshold) << ' '
      << formatDouble(params_.rearmThreshold) << ' ' << formatDouble(params_.alpha) << '\n';
  out << "classes";
  for (int m = 0; m < kMovementClassCount; ++m)
    out << ' ' << movementClassName(static_cast<MovementClass>(m));
  out << "\nframes";
  for (auto c : counts_.frames)
    out << ' ' << c;
  out << '\n';
  for (int s = 0; s < kLmaSymbolCount; ++s) {
    out << "symbol " << lmaSymbolName(static_cast<LmaSymbol>(s)) << ' ' << counts_.table[s].size()
        << '\n';
    for (std::size_t v = 0; v < counts_.table[s].size(); ++v) {
      out << "counts " << v;
      for (auto c : counts_.table[s][v])
        out << ' ' << c;
      out << '\n';
    }
  }
  out << "end\n";
  return out.str();
}

MovementModel MovementModel::parse(const std::string& text, const std::string& source) {
  Reader r(text, source);
  {
    std::istringstream first(text);
    std::string magic, version;
    first >> magic >> version;
    if (magic != kMagic)
      throw Error("'" + source + "' is not a horopter movement model (it must start with '" +
                  kMagic + " " + std::to_string(kFormatVersion) +
                  "'); write one with horopter train");
    if (version != std::to_string(kFormatVersion))
      throw Error("movement model '" + source + "' has format version " + version +
                  ", this horopter reads version " + std::to_string(kFormatVersion) +
                  "; write a new one with horopter train");
  }
  r.next(kMagic);
  MovementModelParams params;
  {
    const auto rec = r.next("params");
    r.expectSize(rec, 6);
    params = {r.number(rec[1]), r.number(rec[2]), r.number(rec[3]), r.number(rec[4]),
              r.number(rec[5])};
  }
  {
    const auto rec = r.next("classes");
    r.expectSize(rec, 1 + kMovementClassCount);
    for (int m = 0; m < kMovementClassCount; ++m)
      if (rec[1 + m] != movementClassName(static_cast<MovementClass>(m)))
        r.fail("class " + std::to_string(m) + " is '" + rec[1 + m] + "', expected '" +
               movementClassName(static_cast<MovementClass>(m)) + "'");
  }
  MovementCounts counts;
  {
    const auto rec = r.next("frames");
    r.expectSize(rec, 1 + kMovementClassCount);
    for (int m = 0; m < kMovementClassCount; ++m)
      counts.frames[m] = r.count(rec[1 + m]);
  }
  for (int s = 0; s < kLmaSymbolCount; ++s) {
    const auto rec = r.next("symbol");
    r.expectSize(rec, 3);
    const auto symbol = static_cast<LmaSymbol>(s);
    if (rec[1] != lmaSymbolName(symbol))
      r.fail("symbol " + std::to_string(s) + " is '" + rec[1] + "', expected '" +
             lmaSymbolName(symbol) + "'");
    if (r.count(rec[2]) != lmaSymbolCardinality(symbol))
      r.fail("symbol '" + rec[1] + "' has " + rec[2] + " values, expected " +
             std::to_string(lmaSymbolCardinality(symbol)));
    for (int v = 0; v < lmaSymbolCardinality(symbol); ++v) {
      const auto c = r.next("counts");
      r.expectSize(c, 2 + kMovementClassCount);
      if (r.count(c[1]) != v) r.fail("expected counts for value " + std::to_string(v));
      for (int m = 0; m < kMovementClassCount; ++m)
        counts.table[s][v][m] = r.count(c[2 + m]);
    }
  }
  r.expectSize(r.next("end"), 1);
  r.expectEnd();
  // Every training frame counts one value of every symbol, so each symbol's
  // counts of a class add up to that class's frames.
  for (int s = 0; s < kLmaSymbolCount; ++s)
    for (int m = 0; m < kMovementClassCount; ++m) {
      std::int64_t sum = 0;
      for (const auto& row : counts.table[s])
        sum += row[m];
      if (sum != counts.frames[m])
        r.fail("symbol '" + std::string(lmaSymbolName(static_cast<LmaSymbol>(s))) + "' counts " +
               std::to_string(sum) + " frames of '" +
               movementClassName(static_cast<MovementClass>(m)) + "', the 'frames' record " +
               std::to_string(counts.frames[m]) + ": the counts are inconsistent");
    }
  try {
    return MovementModel(std::move(counts), params);
  } catch (const Error& e) {
    r.fail(e.what());
  }
}

void MovementModel::save(const std::string& path) const {
  const auto parent = std::filesystem::path(path).parent_path();
  std::error_code ec;
  if (!parent.empty()) std::filesystem::create_directories(parent, ec);
  detail::writeFile(path, serialize(), "movement model");
}

MovementModel MovementModel::load(const std::string& path) {
  if (!std::filesystem::exists(path))
    throw Error("movement model '" + path + "' does not exist; write one with horopter train");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot read the movement model '" + path + "'");
  std::ostringstream text;
  text << in.rdbuf();
  return parse(text.str(), path);
}

}  // namespace horopter
