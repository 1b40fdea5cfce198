// In-process CAN bus: see include/horopter/hardware/can_transports.hpp.
#include "horopter/hardware/can_transports.hpp"

namespace horopter::hw {

class InProcessCanBus::Endpoint final : public CanTransport {
 public:
  Endpoint(std::shared_ptr<Shared> shared, bool host) : shared_(std::move(shared)), host_(host) {}
  void send(const CanFrame& frame) override {
    {
      std::lock_guard lock(shared_->mutex);
      if (shared_->cut) throw LinkError("in-process CAN bus disconnected");
      auto& q = host_ ? shared_->toDevice : shared_->toHost;
      if (q.size() > 4096) q.pop_front();  // a reader that stopped must not grow memory forever
      q.push_back(frame);
    }
    shared_->changed.notify_all();
  }
  bool receive(CanFrame& frame, std::chrono::milliseconds timeout) override {
    std::unique_lock lock(shared_->mutex);
    auto& q = host_ ? shared_->toHost : shared_->toDevice;
    shared_->changed.wait_for(lock, timeout, [&] { return shared_->cut || !q.empty(); });
    if (shared_->cut) throw LinkError("in-process CAN bus disconnected");
    if (q.empty()) return false;
    frame = q.front();
    q.pop_front();
    return true;
  }
  std::string describe() const override { return host_ ? "sim-can:host" : "sim-can:device"; }

 private:
  std::shared_ptr<Shared> shared_;
  bool host_;
};

namespace {
// Forwards to an endpoint owned by the bus (so a driver can own "its" transport).
class Forwarder final : public CanTransport {
 public:
  explicit Forwarder(CanTransport& target) : target_(target) {}
  void send(const CanFrame& f) override { target_.send(f); }
  bool receive(CanFrame& f, std::chrono::milliseconds t) override { return target_.receive(f, t); }
  std::string describe() const override { return target_.describe(); }

 private:
  CanTransport& target_;
};
}  // namespace

InProcessCanBus::InProcessCanBus()
    : shared_(std::make_shared<Shared>()),
      host_(std::make_unique<Endpoint>(shared_, true)),
      device_(std::make_unique<Endpoint>(shared_, false)) {}

std::unique_ptr<CanTransport> InProcessCanBus::takeHostSide() {
  return std::make_unique<Forwarder>(*host_);
}

void InProcessCanBus::disconnect() {
  {
    std::lock_guard lock(shared_->mutex);
    shared_->cut = true;
  }
  shared_->changed.notify_all();
}

bool InProcessCanBus::connected() const {
  std::lock_guard lock(shared_->mutex);
  return !shared_->cut;
}

}  // namespace horopter::hw
