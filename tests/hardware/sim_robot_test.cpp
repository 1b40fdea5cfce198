// SimulatedRobot (real drivers, simulated devices) and the telemetry log.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <thread>

#include <nlohmann/json.hpp>
#include "horopter/core/error.hpp"
#include "horopter/hardware/sim_robot.hpp"

using namespace horopter::hw;
using namespace std::chrono_literals;

TEST(SimulatedRobot, HeadFollowsAndBaseMovesWithTelemetry) {
  SimulatedRobot robot;
  robot.head().command({0.1, -0.05, 0.1}, 1.0);
  const auto path = std::filesystem::temp_directory_path() / "horopter_sim_robot_test.jsonl";
  TelemetryLog log(path.string());
  bool reached = false;
  for (int i = 0; i < 300 && !(reached && robot.trueX() > 0.05); ++i) {  // up to ~3 s
    robot.base().command({0.2, 0.0});
    log.write(robot.sample());
    const auto m = robot.head().measured();
    reached =
        m && std::abs(m->angles.pan - 0.1) < 0.003 && std::abs(m->angles.vergence - 0.1) < 0.004;
    std::this_thread::sleep_for(10ms);
  }
  EXPECT_TRUE(reached);
  EXPECT_GT(robot.trueX(), 0.05);
  const TelemetrySample s = robot.sample();
  ASSERT_TRUE(s.odometry.has_value());
  EXPECT_GT(s.odometry->x, 0.0);
  EXPECT_NEAR(s.odometry->x, robot.trueX(), 0.05);
  robot.shutdown();
  EXPECT_GT(log.lines(), 0);
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line.front(), '{');
  EXPECT_NE(line.find("\"odometry\""), std::string::npos);
  EXPECT_NE(line.find("\"head_measured\""), std::string::npos);
  std::filesystem::remove(path);
}

TEST(TelemetryLog, JsonHasEveryField) {
  TelemetrySample s;
  s.t = 1.5;
  s.headCommanded = HeadAngles{0.1, 0.2, std::nan("")};
  s.emergencyStop = true;
  s.base.lastFault = "say \"hi\"\n";
  const std::string line = TelemetryLog::toJson(s);
  EXPECT_EQ(line.find('\n'), std::string::npos) << "one object per line: " << line;
  const nlohmann::json j = nlohmann::json::parse(line);
  EXPECT_EQ(j.at("t"), 1.5);
  EXPECT_EQ(j.at("head_commanded").at("pan"), 0.1);
  EXPECT_TRUE(j.at("head_commanded").at("vergence").is_null());  // NaN: null, not nan
  EXPECT_TRUE(j.at("head_measured").is_null());
  EXPECT_TRUE(j.at("base_commanded").is_null());
  EXPECT_EQ(j.at("base_sent").at("linear"), 0.0);
  EXPECT_TRUE(j.at("odometry").is_null());
  EXPECT_EQ(j.at("estop"), true);
  EXPECT_EQ(j.at("faults").at("base_last"), "say \"hi\"\n");
  EXPECT_EQ(j.at("faults").at("head_link"), true);
  EXPECT_THROW(TelemetryLog("/nonexistent-dir/x.jsonl"), horopter::Error);
}

TEST(TelemetryLog, AFailedWriteNamesTheLog) {
  if (!std::filesystem::exists("/dev/full")) GTEST_SKIP() << "no /dev/full here";
  TelemetryLog log("/dev/full");  // opens; every write fails with ENOSPC
  try {
    log.write(TelemetrySample{});
    ADD_FAILURE() << "no horopter::Error";
  } catch (const horopter::Error& e) {
    EXPECT_NE(std::string(e.what()).find("telemetry log '/dev/full': No space left on device"),
              std::string::npos)
        << e.what();
  }
  EXPECT_EQ(log.lines(), 0);
}
