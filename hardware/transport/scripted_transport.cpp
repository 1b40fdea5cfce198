// Scripted fake transport: see include/horopter/hardware/scripted_transport.hpp.
#include "horopter/hardware/scripted_transport.hpp"

#include <algorithm>
#include <cstdio>

namespace horopter::hw {

namespace {
std::string hex(const std::vector<std::uint8_t>& v) {
  std::string s;
  char b[4];
  for (auto x : v) {
    std::snprintf(b, sizeof b, "%02X ", x);
    s += b;
  }
  return s;
}
}  // namespace

void ScriptedTransport::expect(std::vector<std::uint8_t> request, std::vector<std::uint8_t> reply) {
  std::lock_guard lock(mutex_);
  script_.push_back({std::move(request), std::move(reply)});
}

void ScriptedTransport::expect(const std::string& request, const std::string& reply) {
  expect(std::vector<std::uint8_t>(request.begin(), request.end()),
         std::vector<std::uint8_t>(reply.begin(), reply.end()));
}

void ScriptedTransport::cut() {
  std::lock_guard lock(mutex_);
  cut_ = true;
}

void ScriptedTransport::write(std::span<const std::uint8_t> bytes) {
  std::lock_guard lock(mutex_);
  if (cut_) throw LinkError("scripted transport cut");
  pendingWrite_.insert(pendingWrite_.end(), bytes.begin(), bytes.end());
  // Match whole requests; a request may arrive in several writes.
  while (!script_.empty() && pendingWrite_.size() >= script_.front().request.size()) {
    Step step = std::move(script_.front());
    script_.pop_front();
    std::vector<std::uint8_t> got(
        pendingWrite_.begin(),
        pendingWrite_.begin() + static_cast<std::ptrdiff_t>(step.request.size()));
    pendingWrite_.erase(pendingWrite_.begin(),
                        pendingWrite_.begin() + static_cast<std::ptrdiff_t>(step.request.size()));
    if (got != step.request) {
      mismatches_.push_back("expected " + hex(step.request) + "got " + hex(got));
      continue;
    }
    readable_.insert(readable_.end(), step.reply.begin(), step.reply.end());
  }
  if (script_.empty() && !pendingWrite_.empty()) {
    mismatches_.push_back("unexpected write " + hex(pendingWrite_));
    pendingWrite_.clear();
  }
}

std::vector<std::uint8_t> ScriptedTransport::read(std::size_t maxBytes, std::chrono::milliseconds) {
  // Never sleeps: silence is an immediate empty read (the caller's timeout has "passed").
  std::lock_guard lock(mutex_);
  if (cut_) throw LinkError("scripted transport cut");
  const std::size_t n = std::min(maxBytes, readable_.size());
  std::vector<std::uint8_t> out(readable_.begin(),
                                readable_.begin() + static_cast<std::ptrdiff_t>(n));
  readable_.erase(readable_.begin(), readable_.begin() + static_cast<std::ptrdiff_t>(n));
  return out;
}

void ScriptedTransport::discardInput() {
  std::lock_guard lock(mutex_);
  readable_.clear();
}

std::vector<std::string> ScriptedTransport::mismatches() const {
  std::lock_guard lock(mutex_);
  return mismatches_;
}

bool ScriptedTransport::scriptDone() const {
  std::lock_guard lock(mutex_);
  return script_.empty();
}

}  // namespace horopter::hw
