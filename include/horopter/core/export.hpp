// What libhoropter.so exports. The library is built with hidden visibility;
// HOROPTER_API marks the public API (classes, free functions) in the
// headers of the layers it holds, so that nothing else -- internal helpers,
// the kernels' per-backend entry points, inline code -- becomes part of its
// ABI. The static libraries the tool, the tests and the Python module link
// carry the same marks, which have no effect there.
#pragma once

#if defined(__GNUC__) || defined(__clang__)
#define HOROPTER_API __attribute__((visibility("default")))
#else
#define HOROPTER_API
#endif
