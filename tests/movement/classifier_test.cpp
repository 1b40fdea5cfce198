// The movement classifier: separable data is learned, the filter decides
// once per movement, models round-trip through their file exactly, and bad
// files are clear errors.
#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <memory>

#include "horopter/core/error.hpp"
#include "horopter/eval/movement_training.hpp"
#include "horopter/movement/movement_classifier.hpp"
#include "test_support.hpp"

namespace horopter {
namespace {

// Valid features whose every symbol is a function of the class: separable.
LmaFeatures separable(MovementClass m, int variant) {
  LmaFeatures f;
  f.valid = true;
  for (int s = 0; s < kLmaSymbolCount; ++s) {
    const int card = lmaSymbolCardinality(static_cast<LmaSymbol>(s));
    // The class fixes the symbol on most variables; a few vary within the class.
    const int v = s % 3 == 0 ? (static_cast<int>(m) + variant) % card : static_cast<int>(m) % card;
    f.symbols[s] = static_cast<std::uint8_t>(v);
  }
  return f;
}

MovementCounts separableCounts() {
  MovementCounts counts;
  for (int m = 0; m < kMovementClassCount; ++m)
    for (int rep = 0; rep < 50; ++rep)
      counts.add(static_cast<MovementClass>(m), separable(static_cast<MovementClass>(m), rep % 2));
  return counts;
}

std::string tempPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() /
          ("horopter_movement_test_" + std::to_string(::getpid()) + "_" + name))
      .string();
}

TEST(MovementClassifier, LearnsSeparableDataAndDecidesEachClassOnce) {
  auto model = std::make_shared<const MovementModel>(separableCounts(), MovementModelParams{});
  for (int m = 1; m < kMovementClassCount; ++m) {
    MovementClassifier c(model);
    int decisions = 0;
    std::optional<MovementClass> first;
    MovementClassifier::Step step;
    for (int i = 0; i < 40; ++i) {
      step = c.update(separable(static_cast<MovementClass>(m), i % 2));
      if (step.decision) {
        ++decisions;
        if (!first) first = step.decision;
      }
    }
    EXPECT_EQ(static_cast<int>(step.likeliest), m);
    EXPECT_GT(step.posterior[m], 0.99);
    ASSERT_TRUE(first.has_value());
    EXPECT_EQ(static_cast<int>(*first), m);
    EXPECT_EQ(decisions, 1) << "one movement, one decision";
  }
}

TEST(MovementClassifier, DecidesAgainOnlyAfterThePosteriorFell) {
  auto model = std::make_shared<const MovementModel>(separableCounts(), MovementModelParams{});
  MovementClassifier c(model);
  int decisions = 0;
  auto run = [&](MovementClass m, int frames) {
    for (int i = 0; i < frames; ++i)
      decisions += c.update(separable(m, i % 2)).decision ? 1 : 0;
  };
  run(MovementClass::Circle, 30);
  run(MovementClass::None, 30);
  run(MovementClass::Circle, 30);
  EXPECT_EQ(decisions, 2);
}

TEST(MovementClassifier, PosteriorSumsToOneAndInvalidFeaturesGiveNoDecision) {
  auto model = std::make_shared<const MovementModel>(separableCounts(), MovementModelParams{});
  MovementClassifier c(model);
  for (int i = 0; i < 50; ++i) {
    const auto step = c.update(LmaFeatures{});
    double sum = 0;
    for (double p : step.posterior)
      sum += p;
    EXPECT_NEAR(sum, 1.0, 1e-12);
    EXPECT_FALSE(step.decision.has_value());
  }
}

TEST(MovementModelFile, ASavedModelReloadsToIdenticalPosteriors) {
  MovementModelParams params;
  params.evidenceWeight = 0.4321;
  const MovementModel original(separableCounts(), params);
  const std::string path = tempPath("roundtrip.hmm");
  original.save(path);
  auto reloaded = std::make_shared<const MovementModel>(MovementModel::load(path));
  std::filesystem::remove(path);
  EXPECT_EQ(reloaded->serialize(), original.serialize());
  EXPECT_EQ(reloaded->params().evidenceWeight, params.evidenceWeight);
  MovementClassifier a(std::make_shared<const MovementModel>(original)), b(reloaded);
  for (int i = 0; i < 60; ++i) {
    const auto f = separable(static_cast<MovementClass>((i / 10) % kMovementClassCount), i % 2);
    const auto sa = a.update(f), sb = b.update(f);
    for (int m = 0; m < kMovementClassCount; ++m)
      ASSERT_EQ(sa.posterior[m], sb.posterior[m]);
    ASSERT_EQ(sa.decision, sb.decision);
  }
}

TEST(MovementModelFile, AWrongVersionIsAClearError) {
  std::string text = MovementModel(separableCounts(), {}).serialize();
  text.replace(text.find(" 1\n"), 3, " 7\n");
  try {
    MovementModel::parse(text, "old.hmm");
    FAIL() << "a version 7 file was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("format version 7"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("horopter train"), std::string::npos) << e.what();
  }
}

TEST(MovementModelFile, AnotherFileTypeIsAClearError) {
  try {
    MovementModel::parse("P5\n640 480\n255\n", "image.pgm");
    FAIL() << "an image was accepted as a model";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("is not a horopter movement model"), std::string::npos)
        << e.what();
  }
}

TEST(MovementModelFile, CorruptAndTruncatedFilesAreClearErrors) {
  const std::string good = MovementModel(separableCounts(), {}).serialize();
  // A count that is not a number.
  std::string corrupt = good;
  const auto at = corrupt.find("counts 0 ");
  corrupt.replace(at + 9, 1, "x");
  EXPECT_THROW(
      {
        try {
          MovementModel::parse(corrupt, "corrupt.hmm");
        } catch (const Error& e) {
          EXPECT_NE(std::string(e.what()).find("corrupt.hmm' line"), std::string::npos) << e.what();
          throw;
        }
      },
      Error);
  // Cut in the middle.
  EXPECT_THROW(MovementModel::parse(good.substr(0, good.size() / 2), "cut.hmm"), Error);
  // Parameters out of range.
  std::string badParams = good;
  badParams.replace(badParams.find("params "), 7, "params 1.5 ");
  EXPECT_THROW(MovementModel::parse(badParams, "params.hmm"), Error);
  // A missing file.
  EXPECT_THROW(MovementModel::load(tempPath("no-such-model.hmm")), Error);
}

TEST(MovementModelFile, TextAfterEndIsAnError) {
  const std::string good = MovementModel(separableCounts(), {}).serialize();
  EXPECT_NO_THROW(MovementModel::parse(good + "\n# a comment\n\n", "comment.hmm"));
  const std::string message =
      test::errorOf([&] { MovementModel::parse(good + "counts 0 1 2 3 4 5 6 7\n", "tail.hmm"); });
  EXPECT_NE(message.find("text after 'end'"), std::string::npos) << message;
  EXPECT_THROW(MovementModel::parse(good.substr(0, good.size() - 1) + " extra\n", "end.hmm"),
               Error);
}

TEST(MovementModelFile, CountsThatDisagreeWithTheFramesAreAnError) {
  std::string text = MovementModel(separableCounts(), {}).serialize();
  // One more frame of class 0 in the frames record than any symbol counted.
  const auto at = text.find("frames ") + 7;
  const auto end = text.find(' ', at);
  text.replace(at, end - at, std::to_string(std::stoll(text.substr(at, end - at)) + 1));
  const std::string message = test::errorOf([&] { MovementModel::parse(text, "sums.hmm"); });
  EXPECT_NE(message.find("inconsistent"), std::string::npos) << message;
}

TEST(MovementModel, ParametersOutOfRangeAreRefused) {
  MovementModelParams p;
  p.stay = 1.0;
  EXPECT_THROW(MovementModel(MovementCounts{}, p), Error);
  p = {};
  p.decisionThreshold = 0.4;
  EXPECT_THROW(MovementModel(MovementCounts{}, p), Error);
}

// The real thing, small: trained on a few synthetic sequences, tested on
// others (seeds from the tuning range).
TEST(MovementTraining, SyntheticSequencesAreLearnedWellAboveChance) {
  TrainingOptions options;
  options.sequences = 40;
  const MovementModel model = trainMovementModel(options);
  std::vector<LabelledSequence> test;
  for (int i = 0; i < 8; ++i)
    test.push_back(syntheticSequence(kTuningSeedBase + 500 + i));
  const double accuracy = frameAccuracy(model, test);
  EXPECT_GT(accuracy, 0.6) << "frame accuracy " << accuracy << " (chance 1/7)";
}

TEST(MovementTraining, SequencesAreDeterministicPerSeedAndDifferBetweenSeeds) {
  const auto a = syntheticSequence(5), b = syntheticSequence(5), c = syntheticSequence(6);
  ASSERT_EQ(a.samples.size(), b.samples.size());
  for (std::size_t i = 0; i < a.samples.size(); ++i) {
    ASSERT_EQ(a.samples[i].rightHand.image, b.samples[i].rightHand.image);
    ASSERT_EQ(a.labels[i], b.labels[i]);
  }
  EXPECT_NE(a.samples[60].rightHand.image, c.samples[60].rightHand.image);
  // Every movement appears in a default-length sequence.
  std::array<bool, kMovementClassCount> seen{};
  for (auto l : a.labels)
    seen[static_cast<int>(l)] = true;
  for (int m = 0; m < kMovementClassCount; ++m)
    EXPECT_TRUE(seen[m]) << movementClassName(static_cast<MovementClass>(m));
}

}  // namespace
}  // namespace horopter
