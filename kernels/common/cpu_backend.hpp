// The CPU backend for the work a device backend leaves on the CPU (the
// OpenCL path's speckle filter, and the OpenCL front end's fallback).
#pragma once

#include "horopter/kernels/backend.hpp"

namespace horopter {

// The CPU backend (scalar or avx2) that HOROPTER_BACKEND names, when it names
// one that is available; otherwise the best available CPU backend. So
// HOROPTER_BACKEND=scalar keeps every kernel, these included, off AVX2, and a
// CPU without AVX2 never gets it. Read at each call, as findBackend() does.
const Backend& cpuBackend();

}  // namespace horopter
