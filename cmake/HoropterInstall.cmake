# What `cmake --install` ships:
#   include/horopter/          the public headers (C++ by layer, and horopter.h)
#   lib/libhoropter.so         the engine, kernels and C API
#   bin/horopter               the command-line tool
#   lib/cmake/horopter/        find_package(horopter) -> horopter::horopter
#   lib/pkgconfig/horopter.pc  pkg-config --cflags --libs horopter
include(CMakePackageConfigHelpers)

set(HOROPTER_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/horopter")

install(TARGETS horopter_library EXPORT horopterTargets
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS horopter RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# The simulator's and the evaluations' headers stay behind: libhoropter has
# neither (they are the tool's and the Python module's).
install(DIRECTORY "${PROJECT_SOURCE_DIR}/include/horopter"
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
  FILES_MATCHING PATTERN "*.hpp" PATTERN "*.h"
  PATTERN "sim" EXCLUDE
  PATTERN "eval" EXCLUDE)

install(EXPORT horopterTargets
  NAMESPACE horopter::
  FILE horopterTargets.cmake
  DESTINATION ${HOROPTER_INSTALL_CMAKEDIR})
# The OpenCV modules the library links, for find_dependency in the config.
string(REPLACE "opencv_" "" HOROPTER_OPENCV_COMPONENTS "${OpenCV_LIBS}")
string(REPLACE ";" " " HOROPTER_OPENCV_COMPONENTS "${HOROPTER_OPENCV_COMPONENTS}")
configure_package_config_file("${PROJECT_SOURCE_DIR}/cmake/horopterConfig.cmake.in"
  "${PROJECT_BINARY_DIR}/horopterConfig.cmake"
  INSTALL_DESTINATION ${HOROPTER_INSTALL_CMAKEDIR})
write_basic_package_version_file("${PROJECT_BINARY_DIR}/horopterConfigVersion.cmake"
  VERSION ${PROJECT_VERSION}
  COMPATIBILITY SameMinorVersion)  # 0.x: minor versions may break the API
install(FILES "${PROJECT_BINARY_DIR}/horopterConfig.cmake"
              "${PROJECT_BINARY_DIR}/horopterConfigVersion.cmake"
  DESTINATION ${HOROPTER_INSTALL_CMAKEDIR})

# The .pc file finds the prefix from its own place, so `cmake --install
# --prefix DIR` gives a working file wherever DIR is.
file(RELATIVE_PATH HOROPTER_PC_TO_PREFIX "/p/${CMAKE_INSTALL_LIBDIR}/pkgconfig" "/p")
configure_file("${PROJECT_SOURCE_DIR}/cmake/horopter.pc.in" "${PROJECT_BINARY_DIR}/horopter.pc" @ONLY)
install(FILES "${PROJECT_BINARY_DIR}/horopter.pc" DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
