// Per-movement scoring; see include/horopter/eval/movement_scoring.hpp.
#include "horopter/eval/movement_scoring.hpp"

#include <algorithm>

namespace horopter {

std::vector<MovementSegment> scoreSegments(const std::vector<ScoredFrame>& frames,
                                           int graceFrames) {
  std::vector<MovementSegment> segments;
  const auto n = static_cast<std::int64_t>(frames.size());
  for (std::int64_t i = 0; i < n;) {
    std::int64_t j = i;
    while (j + 1 < n && frames[j + 1].truth == frames[i].truth)
      ++j;
    std::int64_t interacting = 0;
    for (std::int64_t k = i; k <= j; ++k)
      interacting += frames[k].interacting ? 1 : 0;
    if (frames[i].truth != MovementClass::None && j + 1 < n && 2 * interacting > j - i + 1) {
      MovementSegment s;
      s.truth = frames[i].truth;
      s.firstFrame = i;
      s.lastFrame = j;
      std::int64_t on = 0;
      for (std::int64_t k = i; k <= j; ++k)
        on += frames[k].onTarget ? 1 : 0;
      s.trackerLost = 2 * on < j - i + 1;
      // The window ends before the next movement begins.
      std::int64_t end = std::min(n - 1, j + std::max(0, graceFrames));
      for (std::int64_t k = j + 1; k <= end; ++k)
        if (frames[k].truth != MovementClass::None) {
          end = k - 1;
          break;
        }
      for (std::int64_t k = i; k <= end && !s.decided; ++k)
        if (frames[k].decision) s.decided = frames[k].decision;
      segments.push_back(s);
    }
    i = j + 1;
  }
  return segments;
}

void MovementScore::add(const MovementScore& o) {
  segments += o.segments;
  lost += o.lost;
  correct += o.correct;
  correctTracked += o.correctTracked;
  spurious += o.spurious;
}

MovementScore summariseSegments(const std::vector<ScoredFrame>& frames, int graceFrames) {
  const std::vector<MovementSegment> segments = scoreSegments(frames, graceFrames);
  MovementScore score;
  std::vector<bool> covered(frames.size(), false);
  for (const MovementSegment& s : segments) {
    ++score.segments;
    score.lost += s.trackerLost ? 1 : 0;
    score.correct += s.correct() ? 1 : 0;
    score.correctTracked += s.correct() && !s.trackerLost ? 1 : 0;
    const auto end = std::min<std::int64_t>(static_cast<std::int64_t>(frames.size()) - 1,
                                            s.lastFrame + graceFrames);
    for (std::int64_t k = s.firstFrame; k <= end; ++k)
      covered[k] = true;
  }
  for (std::size_t k = 0; k < frames.size(); ++k)
    if (frames[k].decision && !covered[k]) ++score.spurious;
  return score;
}

}  // namespace horopter
