# Installs the build into WORK_DIR/prefix, then builds and runs three
# consumers against the installed tree only:
#  - README.md's find_package block, copied as written into a CMakeLists.txt
#    beside readme_consumer/app.cpp (it sets no C++ standard: the imported
#    target must carry C++20);
#  - examples/cpp (find_package(horopter), target horopter::horopter): embed
#    and embed_c;
#  - examples/cpp/embed_c.c compiled by hand with `pkg-config --cflags --libs horopter`,
#    and pkg-config's answers checked: -lhoropter alone for --libs (OpenCV and
#    Eigen are Requires.private), their headers for --cflags.
# Run by ctest as `cmake -P` (see CMakeLists.txt beside this file).
cmake_minimum_required(VERSION 3.25)

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message(STATUS "$ ${ARGN}\n${out}${err}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}")
  endif()
  set(last_output "${out}" PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE "${WORK_DIR}")
set(prefix "${WORK_DIR}/prefix")
run(${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${prefix}")

foreach(f include/horopter/horopter.h include/horopter/vision/frontend.hpp bin/horopter)
  if(NOT EXISTS "${prefix}/${f}")
    message(FATAL_ERROR "the install tree has no ${f}")
  endif()
endforeach()
file(GLOB_RECURSE configs "${prefix}/*/horopterConfig.cmake")
file(GLOB_RECURSE pcs "${prefix}/*/horopter.pc")
if(NOT configs OR NOT pcs)
  message(FATAL_ERROR "the install tree lacks horopterConfig.cmake or horopter.pc")
endif()

# The consumer projects see only the install tree.
set(consumer_flags "-DCMAKE_BUILD_TYPE=Release" "-DCMAKE_PREFIX_PATH=${prefix}"
    "-DCMAKE_CXX_FLAGS=${EXTRA_FLAGS}" "-DCMAKE_C_FLAGS=${EXTRA_FLAGS}"
    "-DCMAKE_EXE_LINKER_FLAGS=${EXTRA_FLAGS}")

# README.md: the ```cmake block that calls find_package(horopter), verbatim.
file(READ "${SOURCE_DIR}/README.md" readme)
string(REGEX MATCH "```cmake\n([^`]*find_package\\(horopter[^`]*)```" block "${readme}")
if(NOT block)
  message(FATAL_ERROR "README.md has no ```cmake block with find_package(horopter)")
endif()
set(readme_dir "${WORK_DIR}/readme_consumer")
file(WRITE "${readme_dir}/CMakeLists.txt" "${CMAKE_MATCH_1}")
file(COPY "${SOURCE_DIR}/tests/bindings/readme_consumer/app.cpp" DESTINATION "${readme_dir}")
message(STATUS "README's consumer:\n${CMAKE_MATCH_1}")
run(${CMAKE_COMMAND} -S "${readme_dir}" -B "${readme_dir}/build" -G "${GENERATOR}" ${consumer_flags})
run(${CMAKE_COMMAND} --build "${readme_dir}/build")
run("${readme_dir}/build/app")

run(${CMAKE_COMMAND} -S "${SOURCE_DIR}/examples/cpp" -B "${WORK_DIR}/build" -G "${GENERATOR}"
    ${consumer_flags})
run(${CMAKE_COMMAND} --build "${WORK_DIR}/build")
run("${WORK_DIR}/build/embed" --frames 2)
if(NOT last_output MATCHES "inside the zone")
  message(FATAL_ERROR "embed did not report the zone")
endif()
run("${WORK_DIR}/build/embed_c")

# pkg-config: the flags alone build and link the C example.
find_program(PKG_CONFIG pkg-config REQUIRED)
get_filename_component(pcdir "${pcs}" DIRECTORY)
set(ENV{PKG_CONFIG_PATH} "${pcdir}")
run(${PKG_CONFIG} --cflags --libs horopter)
string(STRIP "${last_output}" flags)
separate_arguments(flags UNIX_COMMAND "${flags}")
separate_arguments(extra UNIX_COMMAND "${EXTRA_FLAGS}")
get_filename_component(libdir "${pcs}" DIRECTORY)
get_filename_component(libdir "${libdir}" DIRECTORY)
run(${C_COMPILER} ${extra} "${SOURCE_DIR}/examples/cpp/embed_c.c" -o "${WORK_DIR}/embed_c_pkgconfig"
    ${flags} "-Wl,-rpath,${libdir}")
run("${WORK_DIR}/embed_c_pkgconfig")
# OpenCV and Eigen are private requirements: a consumer of the shared library
# links -lhoropter alone; --cflags still finds their headers (the C++ API's),
# --static their libraries.
run(${PKG_CONFIG} --libs horopter)
if(last_output MATCHES "opencv|-lhoropter.*-l")
  message(FATAL_ERROR "pkg-config --libs horopter gives more than -lhoropter: ${last_output}")
endif()
if(NOT last_output MATCHES "-lhoropter")
  message(FATAL_ERROR "pkg-config --libs horopter lacks -lhoropter: ${last_output}")
endif()
run(${PKG_CONFIG} --print-requires horopter)
string(STRIP "${last_output}" last_output)
if(NOT last_output STREQUAL "")
  message(FATAL_ERROR "horopter.pc has public requirements: ${last_output}")
endif()
run(${PKG_CONFIG} --print-requires-private horopter)
if(NOT last_output MATCHES "opencv4" OR NOT last_output MATCHES "eigen3")
  message(FATAL_ERROR "horopter.pc lacks the private opencv4 and eigen3: ${last_output}")
endif()
run(${PKG_CONFIG} --cflags horopter)
if(NOT last_output MATCHES "opencv4" OR NOT last_output MATCHES "eigen3")
  message(FATAL_ERROR "pkg-config --cflags horopter lacks OpenCV's or Eigen's headers: ${last_output}")
endif()
run(${PKG_CONFIG} --libs --static horopter)
if(NOT last_output MATCHES "-lopencv_core")
  message(FATAL_ERROR "pkg-config --libs --static horopter lacks OpenCV: ${last_output}")
endif()
message(STATUS "install consumer: passed")
