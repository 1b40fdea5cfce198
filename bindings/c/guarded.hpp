// What every C entry point shares: `guarded` runs a body and turns any
// exception into a status and the thread's last-error message, so nothing
// crosses into C. Internal to bindings/c.
#pragma once

#include <exception>
#include <new>
#include <string>

#include "horopter/core/error.hpp"
#include "horopter/horopter.h"
#include "horopter/kernels/stereo_params.hpp"

// Shared by the C API's files, exported by none (libhoropter.map exports
// the horopter namespace; these helpers are not its API).
#pragma GCC visibility push(hidden)
namespace horopter::c_api {

inline thread_local std::string tLastError;

// An argument the caller got wrong (the library's own horopter::Error is
// about bad input too), and a file or device that failed.
struct InvalidArgument : horopter::Error {
  using horopter::Error::Error;
};
struct Failed : horopter::Error {
  using horopter::Error::Error;
};

// `message` with the C++ members it names (numDisparities) written as the C
// structs' fields (num_disparities): c_names.cpp.
std::string inCNames(std::string message);

inline void storeMessage(const char* what) noexcept {
  try {
    tLastError = inCNames(what);
  } catch (...) {  // out of memory while rewriting: an empty message, no exception
    tLastError.clear();
  }
}

template <typename Fn>
horopter_status guarded(Fn&& fn) noexcept {
  try {
    fn();
    return HOROPTER_OK;
  } catch (const Failed& e) {
    storeMessage(e.what());
    return HOROPTER_ERROR_FAILED;
  } catch (const horopter::Error& e) {
    storeMessage(e.what());
    return HOROPTER_ERROR_INVALID_ARGUMENT;
  } catch (const std::bad_alloc&) {
    tLastError = "out of memory";
    return HOROPTER_ERROR_OUT_OF_MEMORY;
  } catch (const std::exception& e) {
    tLastError = std::string("internal error: ") + e.what();
    return HOROPTER_ERROR_INTERNAL;
  } catch (...) {
    tLastError = "internal error: unknown exception";
    return HOROPTER_ERROR_INTERNAL;
  }
}

template <typename T>
void requireNonNull(const T* p, const char* what) {
  if (!p) throw InvalidArgument(std::string(what) + " is NULL");
}

// The C parameters as the library's (validated where they are used).
void paramsOf(const horopter_stereo_params& c, StereoParams& s, MedianParams& m);

}  // namespace horopter::c_api
#pragma GCC visibility pop
