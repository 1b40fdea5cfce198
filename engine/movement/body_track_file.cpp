// Recorded tracks as CSV; see include/horopter/movement/body_track_file.hpp.
#include "horopter/movement/body_track_file.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "file_output.hpp"
#include "horopter/core/error.hpp"

namespace horopter {

namespace {

constexpr const char* kMagic = "# horopter-body-track 1";
constexpr int kColumns = 3 + 3 * 7;

std::string header() {
  std::string h = "frame,time_s,godfather";
  for (const char* part : {"head", "left_hand", "right_hand"})
    for (const char* field : {"tracked", "observed", "u", "v", "x", "y", "z"})
      h += std::string(",") + part + "_" + field;
  return h;
}

}  // namespace

void writeBodyTrack(const std::string& path, const std::vector<BodySample>& samples,
                    const std::vector<MovementClass>& truth) {
  if (!truth.empty() && truth.size() != samples.size())
    throw Error("writeBodyTrack: one truth label per sample, or none");
  const auto parent = std::filesystem::path(path).parent_path();
  std::error_code ec;
  if (!parent.empty()) std::filesystem::create_directories(parent, ec);
  std::ostringstream out;
  out << kMagic << '\n' << header() << (truth.empty() ? "" : ",truth") << '\n';
  std::size_t index = 0;
  char buf[160];
  for (const BodySample& s : samples) {
    std::snprintf(buf, sizeof buf, "%lld,%.6f,%d", static_cast<long long>(s.frame), s.timeS,
                  s.godfather ? 1 : 0);
    out << buf;
    for (const PartState* p : {&s.head, &s.leftHand, &s.rightHand}) {
      std::snprintf(buf, sizeof buf, ",%d,%d,%.3f,%.3f,%.5f,%.5f,%.5f", p->tracked ? 1 : 0,
                    p->observed ? 1 : 0, p->image.x, p->image.y, p->rig.x, p->rig.y, p->rig.z);
      out << buf;
    }
    if (!truth.empty()) out << ',' << movementClassName(truth[index]);
    ++index;
    out << '\n';
  }
  detail::writeFile(path, out.str(), "track file");
}

std::vector<BodySample> readBodyTrack(const std::string& path, std::vector<MovementClass>* truth) {
  if (truth) truth->clear();
  if (!std::filesystem::exists(path)) throw Error("track file '" + path + "' does not exist");
  std::ifstream in(path);
  if (!in) throw Error("cannot read the track file '" + path + "'");
  std::string line;
  int lineNo = 0;
  auto fail = [&](const std::string& what) {
    throw Error("track file '" + path + "' line " + std::to_string(lineNo) + ": " + what);
  };
  std::getline(in, line);
  ++lineNo;
  if (line != kMagic)
    fail(std::string("not a horopter body track (the first line must be '") + kMagic + "')");
  std::getline(in, line);
  ++lineNo;
  const bool labelled = line == header() + ",truth";
  if (line != header() && !labelled) fail("unexpected column header");
  std::vector<BodySample> samples;
  while (std::getline(in, line)) {
    ++lineNo;
    if (line.empty()) continue;
    std::vector<double> v;
    if (labelled) {
      const auto comma = line.rfind(',');
      const auto label = movementClassFromName(line.substr(comma + 1));
      if (comma == std::string::npos || !label)
        fail("the truth column holds '" + line.substr(comma + 1) + "', not a movement name");
      if (truth) truth->push_back(*label);
      line.erase(comma);
    }
    std::stringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) {
      if (cell == "nan" || cell == "-nan") {
        v.push_back(std::nan(""));
        continue;
      }
      std::size_t used = 0;
      double x = 0;
      try {
        x = std::stod(cell, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != cell.size() || cell.empty()) fail("'" + cell + "' is not a number");
      v.push_back(x);
    }
    if (static_cast<int>(v.size()) != kColumns)
      fail(std::to_string(v.size()) + " columns, expected " + std::to_string(kColumns));
    // A frame number is a whole number a double holds exactly; the cast of
    // NaN or 1e300 to an integer is undefined (found by
    // tests/fuzz/body_track_fuzz.cpp).
    if (!(v[0] >= -9007199254740992.0 && v[0] <= 9007199254740992.0) || v[0] != std::floor(v[0]))
      fail("frame must be a whole number, not '" + std::to_string(v[0]) + "'");
    BodySample s;
    s.frame = static_cast<std::int64_t>(v[0]);
    s.timeS = v[1];
    s.godfather = v[2] != 0;
    if (!std::isfinite(s.timeS)) fail("time_s must be finite");
    int c = 3;
    for (PartState* p : {&s.head, &s.leftHand, &s.rightHand}) {
      p->tracked = v[c] != 0;
      p->observed = v[c + 1] != 0;
      p->image = {static_cast<float>(v[c + 2]), static_cast<float>(v[c + 3])};
      p->rig = {static_cast<float>(v[c + 4]), static_cast<float>(v[c + 5]),
                static_cast<float>(v[c + 6])};
      c += 7;
    }
    if (!samples.empty() && !(s.timeS > samples.back().timeS))
      fail("time_s must increase from line to line");
    samples.push_back(s);
  }
  return samples;
}

}  // namespace horopter
