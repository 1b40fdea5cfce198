# Installs the build into WORK_DIR/prefix, then builds and runs two consumers
# against the installed tree only:
#  - examples/cpp (find_package(horopter), target horopter::horopter): embed
#    and embed_c;
#  - examples/cpp/embed_c.c compiled by hand with `pkg-config --cflags --libs horopter`.
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

foreach(f include/horopter/horopter.h include/horopter/frontend.hpp bin/horopter)
  if(NOT EXISTS "${prefix}/${f}")
    message(FATAL_ERROR "the install tree has no ${f}")
  endif()
endforeach()
file(GLOB_RECURSE configs "${prefix}/*/horopterConfig.cmake")
file(GLOB_RECURSE pcs "${prefix}/*/horopter.pc")
if(NOT configs OR NOT pcs)
  message(FATAL_ERROR "the install tree lacks horopterConfig.cmake or horopter.pc")
endif()

# The consumer project sees only the install tree.
run(${CMAKE_COMMAND} -S "${SOURCE_DIR}/examples/cpp" -B "${WORK_DIR}/build" -G "${GENERATOR}"
    -DCMAKE_BUILD_TYPE=Release "-DCMAKE_PREFIX_PATH=${prefix}"
    "-DCMAKE_CXX_FLAGS=${EXTRA_FLAGS}" "-DCMAKE_C_FLAGS=${EXTRA_FLAGS}"
    "-DCMAKE_EXE_LINKER_FLAGS=${EXTRA_FLAGS}")
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
message(STATUS "install consumer: passed")
