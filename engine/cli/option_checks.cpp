#include "option_checks.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "args.hpp"
#include "horopter/kernels/backend.hpp"

namespace horopter::cli {

namespace fs = std::filesystem;

void requireFile(const std::string& path, const std::string& what) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw UsageError(what + " '" + path + "' does not exist");
  if (fs::is_directory(path, ec))
    throw UsageError(what + " '" + path + "' is a folder, not a file");
}

void requireWritableFolder(const std::string& dir, const std::string& flag) {
  const std::string prefix = flag + ": cannot write to the folder '" + dir + "': ";
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw UsageError(prefix + ec.message());
  if (!fs::is_directory(dir, ec)) throw UsageError(prefix + "it is not a folder");
  if (access(dir.c_str(), W_OK | X_OK) != 0) throw UsageError(prefix + std::strerror(errno));
}

void requireWritableFile(const std::string& file, const std::string& flag) {
  std::error_code ec;
  if (fs::exists(file, ec)) {
    if (fs::is_directory(file, ec))
      throw UsageError(flag + ": '" + file + "' is a folder, not a file");
    if (access(file.c_str(), W_OK) != 0)
      throw UsageError(flag + ": cannot write '" + file + "': " + std::strerror(errno));
    return;
  }
  const fs::path parent = fs::path(file).parent_path();
  requireWritableFolder(parent.empty() ? "." : parent.string(), flag);
}

void requireBackend(const std::string& name) {
  asUsageError([&] { findBackend(name); });
}

}  // namespace horopter::cli
