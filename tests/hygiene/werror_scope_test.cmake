# -Werror in our own builds only: the top-level build (CI's) compiles with it,
# and the standalone Python build that `pip install ./bindings/python` runs,
# where Horopter is a subproject, compiles the same sources without it (with
# the warnings still on). Configures that build into WORK_DIR (no compiling).
# Run by ctest as `cmake -P` (tests/hygiene/CMakeLists.txt).
cmake_minimum_required(VERSION 3.25)

function(compile_command_of build_dir source out)
  file(READ "${build_dir}/compile_commands.json" commands)
  string(REGEX MATCH "\"command\": \"[^\"]*${source}\"" command "${commands}")
  if(NOT command)
    message(FATAL_ERROR "${build_dir}/compile_commands.json does not compile ${source}")
  endif()
  set(${out} "${command}" PARENT_SCOPE)
endfunction()

compile_command_of("${BUILD_DIR}" "kernels/sad/sad_avx2.cpp" top)
if(NOT top MATCHES " -Werror " OR NOT top MATCHES " -Wall ")
  message(FATAL_ERROR "the top-level build should compile with -Wall -Werror:\n${top}")
endif()

if(NOT PYTHON_MODULE)
  message(STATUS "werror_scope: skipped: the Python module is not built here (no pybind11)")
  return()
endif()
file(REMOVE_RECURSE "${WORK_DIR}")
execute_process(
  COMMAND ${CMAKE_COMMAND} -S "${SOURCE_DIR}/bindings/python" -B "${WORK_DIR}" -G "${GENERATOR}"
          -DCMAKE_BUILD_TYPE=Release -DCMAKE_EXPORT_COMPILE_COMMANDS=ON
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "configuring bindings/python on its own failed:\n${out}${err}")
endif()
compile_command_of("${WORK_DIR}" "kernels/sad/sad_avx2.cpp" sub)
if(sub MATCHES "-Werror" OR NOT sub MATCHES " -Wall ")
  message(FATAL_ERROR "the pip build should compile with -Wall and without -Werror:\n${sub}")
endif()
message(STATUS "werror_scope: passed: -Werror at the top level, not in the pip build:\n${sub}")
