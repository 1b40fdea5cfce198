// Writing the files the tool and the library produce, every write checked:
// a full disk, a missing folder or a closed device is a horopter::Error
// naming the file and the reason ("cannot write the run summary
// 'out/summary.json': No space left on device"), never a silently short file.
#pragma once

#include <ostream>
#include <string>
#include <string_view>

namespace horopter::detail {

// Writes `bytes` to `path`, replacing the file. `what` names the file for the
// message ("run summary"). Throws horopter::Error when the file cannot be
// opened, written, flushed or closed.
void writeFile(const std::string& path, std::string_view bytes, const std::string& what);

// For a file written in place over time (a log): flushes `out`, opened on
// `path`, and throws horopter::Error as writeFile does if any write to it failed.
void checkStream(std::ostream& out, const std::string& path, const std::string& what);

// "cannot write the <what> '<path>': <strerror(error)>" (error 0: no reason known).
[[noreturn]] void throwWriteError(const std::string& what, const std::string& path, int error);

}  // namespace horopter::detail
