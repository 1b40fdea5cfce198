/* Horopter's version: the one source of it. The top-level CMakeLists.txt
 * reads these three numbers into project(horopter VERSION ...), from which
 * `horopter --version`, horopter_version(), horopter.__version__, the CMake
 * package version and pkg-config's follow; the Python package's
 * pyproject.toml must carry the same (its test checks). Usable from C and C++.
 *
 * Bump a release by editing the three numbers and the string below. */
#ifndef HOROPTER_VERSION_H
#define HOROPTER_VERSION_H

#define HOROPTER_VERSION_MAJOR 0
#define HOROPTER_VERSION_MINOR 1
#define HOROPTER_VERSION_PATCH 0
/* "MAJOR.MINOR.PATCH" (CMake checks that it matches the numbers). */
#define HOROPTER_VERSION_STRING "0.1.0"
/* One comparable number: MAJOR * 10000 + MINOR * 100 + PATCH. */
#define HOROPTER_VERSION_NUMBER \
  (HOROPTER_VERSION_MAJOR * 10000 + HOROPTER_VERSION_MINOR * 100 + HOROPTER_VERSION_PATCH)

#endif /* HOROPTER_VERSION_H */
