// Checks of what an option names, made while the options are parsed, before
// a command starts its work: a file that must exist, a folder that must be
// writable, a backend that must be known. Each throws a UsageError.
#pragma once

#include <string>

namespace horopter::cli {

// "<what> '<path>' does not exist" (or is not a file).
void requireFile(const std::string& path, const std::string& what);

// Creates the folder when missing; "<flag>: cannot write to the folder
// '<dir>': <why>" when that fails or the folder is not writable.
void requireWritableFolder(const std::string& dir, const std::string& flag);

// A file to be written: writable when it exists (a device such as
// /dev/stdout too), else its folder (created when missing; "." for a bare name).
void requireWritableFile(const std::string& file, const std::string& flag);

// findBackend(name): its error for an unknown name (which names "backend")
// or a backend this machine lacks.
void requireBackend(const std::string& name);

}  // namespace horopter::cli
