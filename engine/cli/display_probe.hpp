// Whether a window can be opened, asked of a child process: OpenCV's Qt
// back end aborts the whole process (SIGABRT) when DISPLAY names an X server
// that does not answer, so `run --display` cannot simply try and catch.
#pragma once

namespace horopter::cli {

// The hidden command the probe runs in the child: opens and closes a window.
inline constexpr const char* kDisplayProbeCommand = "__probe-display";

// Throws horopter::Error naming DISPLAY when no window can be opened.
void checkDisplayOpens();

// The child's side: 0 when the window opened (any failure aborts inside Qt).
int probeDisplay();

}  // namespace horopter::cli
