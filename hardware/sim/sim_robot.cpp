// The simulated robot: see include/horopter/hardware/sim_robot.hpp.
#include "horopter/hardware/sim_robot.hpp"

#include <mutex>

#include "horopter/hardware/can_transports.hpp"
#include "horopter/hardware/dynamixel_head.hpp"
#include "horopter/hardware/serial_port.hpp"
#include "horopter/hardware/sim_devices.hpp"
#include "horopter/hardware/sim_rmp.hpp"

namespace horopter::hw {

namespace {

// Records what the pipeline asked, then forwards to the driver.
class RecordingHead final : public Head {
 public:
  explicit RecordingHead(std::unique_ptr<DynamixelHead> h) : head_(std::move(h)) {}
  std::string name() const override { return head_->name(); }
  HeadLimits limits() const override { return head_->limits(); }
  void command(const HeadAngles& t, double s) override {
    head_->command(t, s);
    std::lock_guard lock(mutex_);
    last_ = t;
  }
  std::optional<HeadMeasurement> measured() const override { return head_->measured(); }
  void halt() override { head_->halt(); }
  std::optional<HeadAngles> lastCommand() const {
    std::lock_guard lock(mutex_);
    return last_;
  }
  DynamixelHead& driver() { return *head_; }

 private:
  std::unique_ptr<DynamixelHead> head_;
  mutable std::mutex mutex_;
  std::optional<HeadAngles> last_;
};

class RecordingBase final : public Base {
 public:
  explicit RecordingBase(std::unique_ptr<RmpBase> b) : base_(std::move(b)) {}
  std::string name() const override { return base_->name(); }
  void command(const BaseVelocity& v) override {
    base_->command(v);
    std::lock_guard lock(mutex_);
    last_ = v;
  }
  void emergencyStop() override { base_->emergencyStop(); }
  void releaseEmergencyStop() override { base_->releaseEmergencyStop(); }
  bool emergencyStopped() const override { return base_->emergencyStopped(); }
  std::optional<Odometry> odometry() const override { return base_->odometry(); }
  std::optional<BaseVelocity> lastCommand() const {
    std::lock_guard lock(mutex_);
    return last_;
  }
  RmpBase& driver() { return *base_; }

 private:
  std::unique_ptr<RmpBase> base_;
  mutable std::mutex mutex_;
  std::optional<BaseVelocity> last_;
};

}  // namespace

struct SimulatedRobot::Impl {
  Clock::time_point start = Clock::now();
  std::unique_ptr<SimDynamixelBus> servos;
  InProcessCanBus can;
  std::unique_ptr<SimRmp> rmp;
  std::unique_ptr<RecordingHead> head;
  std::unique_ptr<RecordingBase> base;
};

SimulatedRobot::SimulatedRobot(SimulatedRobotOptions options) : impl_(std::make_unique<Impl>()) {
  std::vector<std::uint8_t> ids = {1, 2};
  DynamixelHeadOptions ho;
  if (options.vergence) {
    ids.push_back(3);
    ids.push_back(4);
    ho.leftVergenceId = 3;
    ho.rightVergenceId = 4;
    ho.limits.vergenceMin = 0;
    ho.limits.vergenceMax = 0.5;
  }
  impl_->servos = std::make_unique<SimDynamixelBus>(ids);
  impl_->head = std::make_unique<RecordingHead>(
      std::make_unique<DynamixelHead>(std::make_unique<SerialPort>(impl_->servos->port()), ho));
  impl_->rmp = std::make_unique<SimRmp>(impl_->can.deviceSide());
  RmpBaseOptions bo = options.base;
  bo.startThread = true;
  impl_->base =
      std::make_unique<RecordingBase>(std::make_unique<RmpBase>(impl_->can.takeHostSide(), bo));
}

SimulatedRobot::~SimulatedRobot() {
  shutdown();
}

Head& SimulatedRobot::head() {
  return *impl_->head;
}
Base& SimulatedRobot::base() {
  return *impl_->base;
}

TelemetrySample SimulatedRobot::sample() const {
  TelemetrySample s;
  s.t = std::chrono::duration<double>(Clock::now() - impl_->start).count();
  s.headCommanded = impl_->head->lastCommand();
  s.headMeasured = impl_->head->measured();
  s.head = impl_->head->driver().health();
  s.baseCommanded = impl_->base->lastCommand();
  s.base = impl_->base->driver().health();
  s.baseSent = s.base.lastSent;
  s.odometry = impl_->base->odometry();
  s.emergencyStop = impl_->base->emergencyStopped();
  return s;
}

double SimulatedRobot::trueX() const {
  return impl_->rmp->truth().x;
}

void SimulatedRobot::shutdown() {
  if (!impl_) return;
  impl_->base->driver().shutdown();
  impl_->head->driver().shutdown();
  impl_->rmp->stop();
}

}  // namespace horopter::hw
