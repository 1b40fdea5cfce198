// A fake ByteTransport for protocol and driver tests: a script of expected
// requests, each answered with given bytes or with silence; a mismatch is
// recorded (and the reply withheld), and the link can be cut.
#pragma once

#include "horopter/core/export.hpp"

#include <deque>
#include <mutex>
#include <string>
#include <vector>

#include "horopter/hardware/transport.hpp"

namespace horopter::hw {

class HOROPTER_API ScriptedTransport final : public ByteTransport {
 public:
  // When `request` is written, `reply` becomes readable (empty: silence).
  void expect(std::vector<std::uint8_t> request, std::vector<std::uint8_t> reply);
  void expect(const std::string& request, const std::string& reply);
  // Every later write or read throws LinkError.
  void cut();

  void write(std::span<const std::uint8_t> bytes) override;
  std::vector<std::uint8_t> read(std::size_t maxBytes, std::chrono::milliseconds timeout) override;
  void discardInput() override;
  std::string describe() const override { return "scripted"; }

  // Writes that did not match the script, as readable text; empty when all did.
  std::vector<std::string> mismatches() const;
  bool scriptDone() const;

 private:
  struct Step {
    std::vector<std::uint8_t> request, reply;
  };
  mutable std::mutex mutex_;
  std::deque<Step> script_;
  std::vector<std::uint8_t> pendingWrite_, readable_;
  std::vector<std::string> mismatches_;
  bool cut_ = false;
};

}  // namespace horopter::hw
