#include "display_probe.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>

#include <opencv2/highgui.hpp>

#include "horopter/core/error.hpp"

extern char** environ;

namespace horopter::cli {

namespace {

std::string displayName() {
  if (const char* d = std::getenv("DISPLAY")) return std::string("DISPLAY=") + d;
  if (const char* w = std::getenv("WAYLAND_DISPLAY")) return std::string("WAYLAND_DISPLAY=") + w;
  return {};
}

}  // namespace

void checkDisplayOpens() {
  const std::string display = displayName();
  if (display.empty())
    throw Error("--display needs a display (DISPLAY is not set): drop --display, or run under X");
  // The child is this program again, with its output (Qt's complaints) dropped.
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addopen(&files, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&files, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  char self[] = "/proc/self/exe";
  std::string command = kDisplayProbeCommand;
  char* argv[] = {self, command.data(), nullptr};
  pid_t child = -1;
  const int spawned = posix_spawn(&child, self, &files, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&files);
  if (spawned != 0)
    throw Error("--display: cannot start the display check (" + std::string(strerror(spawned)) +
                ")");
  // A display that hangs is as useless as one that refuses: 10 s at most.
  int status = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  pid_t done = 0;
  while ((done = waitpid(child, &status, WNOHANG)) == 0 &&
         std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  if (done == 0) {
    kill(child, SIGKILL);
    waitpid(child, &status, 0);
    throw Error("--display: no window opened within 10 s on " + display +
                ": drop --display, or point DISPLAY at a live X server");
  }
  if (done < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw Error("--display: cannot open a window on " + display +
                " (no X server answers there?): drop --display, or point DISPLAY at a live X "
                "server");
}

int probeDisplay() {
  cv::namedWindow("horopter display check", cv::WINDOW_AUTOSIZE);
  cv::destroyAllWindows();
  return 0;
}

}  // namespace horopter::cli
