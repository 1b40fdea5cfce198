// Body track files: a round trip keeps every field (and the truth), and
// malformed files are clear errors.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "horopter/core/error.hpp"
#include "horopter/eval/movement_training.hpp"
#include "horopter/movement/body_track_file.hpp"

namespace horopter {
namespace {

std::string tempPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() /
          ("horopter_track_test_" + std::to_string(::getpid()) + "_" + name))
      .string();
}

TEST(BodyTrackFile, RoundTripKeepsSamplesAndTruth) {
  const LabelledSequence seq = syntheticSequence(11);
  const std::string path = tempPath("roundtrip.csv");
  writeBodyTrack(path, seq.samples, seq.labels);
  std::vector<MovementClass> truth;
  const auto back = readBodyTrack(path, &truth);
  std::filesystem::remove(path);
  ASSERT_EQ(back.size(), seq.samples.size());
  EXPECT_EQ(truth, seq.labels);
  for (std::size_t i = 0; i < back.size(); ++i) {
    const BodySample &a = seq.samples[i], &b = back[i];
    ASSERT_EQ(a.frame, b.frame);
    ASSERT_NEAR(a.timeS, b.timeS, 1e-6);
    ASSERT_EQ(a.godfather, b.godfather);
    for (auto [p, q] : {std::pair{&a.head, &b.head}, std::pair{&a.leftHand, &b.leftHand},
                        std::pair{&a.rightHand, &b.rightHand}}) {
      ASSERT_EQ(p->tracked, q->tracked);
      ASSERT_NEAR(p->image.x, q->image.x, 1e-3);
      ASSERT_NEAR(p->image.y, q->image.y, 1e-3);
      ASSERT_EQ(std::isnan(p->rig.z), std::isnan(q->rig.z));
      if (!std::isnan(p->rig.z)) {
        ASSERT_NEAR(p->rig.z, q->rig.z, 1e-5);
      }
    }
  }
}

TEST(BodyTrackFile, MalformedFilesAreClearErrors) {
  const std::string path = tempPath("bad.csv");
  auto expectError = [&](const std::string& text, const std::string& message) {
    std::ofstream(path) << text;
    try {
      readBodyTrack(path);
      ADD_FAILURE() << "accepted: " << text.substr(0, 60);
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
  };
  expectError("frame,time\n1,2\n", "not a horopter body track");
  const std::string good = tempPath("good.csv");
  writeBodyTrack(good, syntheticSequence(12).samples);
  std::ifstream in(good);
  std::string magic, header, row;
  std::getline(in, magic);
  std::getline(in, header);
  std::getline(in, row);
  std::filesystem::remove(good);
  expectError(magic + "\n" + header + "\n" + row + ",7\n", "columns, expected");
  expectError(magic + "\n" + header + "\n" + row + "\n" + row + "\n", "time_s must increase");
  std::string bad = row;
  bad[bad.find(',') + 1] = 'x';
  expectError(magic + "\n" + header + "\n" + bad + "\n", "is not a number");
  // NaN or huge frame numbers (an undefined cast, found by the fuzz target).
  for (const char* frame : {"nan", "1e300", "-inf", "2.5"})
    expectError(magic + "\n" + header + "\n" + frame + row.substr(row.find(',')) + "\n",
                "frame must be a whole number");
  std::filesystem::remove(path);
  EXPECT_THROW(readBodyTrack(tempPath("missing.csv")), Error);
}

}  // namespace
}  // namespace horopter
