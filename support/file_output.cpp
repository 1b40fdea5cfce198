// See file_output.hpp.
#include "file_output.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "horopter/core/error.hpp"

namespace horopter::detail {

void throwWriteError(const std::string& what, const std::string& path, int error) {
  const std::string reason =
      error != 0 ? std::string(std::strerror(error)) : "the write failed (disk full?)";
  throw Error("cannot write the " + what + " '" + path + "': " + reason);
}

void writeFile(const std::string& path, std::string_view bytes, const std::string& what) {
  errno = 0;
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) throwWriteError(what, path, errno);
  errno = 0;
  int error = 0;
  if (!bytes.empty() && std::fwrite(bytes.data(), 1, bytes.size(), f) != bytes.size())
    error = errno ? errno : EIO;
  // Buffered bytes reach the file here: a full disk shows at the flush or the close.
  if (std::fflush(f) != 0 && error == 0) error = errno ? errno : EIO;
  if (std::fclose(f) != 0 && error == 0) error = errno ? errno : EIO;
  if (error != 0) throwWriteError(what, path, error);
}

void checkStream(std::ostream& out, const std::string& path, const std::string& what) {
  if (out.good()) errno = 0;  // else the failed write's errno, if nothing came since
  out.flush();
  if (!out.good()) throwWriteError(what, path, errno);
}

}  // namespace horopter::detail
