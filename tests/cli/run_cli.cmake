# Runs one command-line test of the `horopter` tool and checks its outcome.
#
#   cmake [-DREQUIRE=file1|file2] [-DEXPECT_EXIT=0|nonzero|N]
#         [-DSTDOUT_REGEX=re] [-DSTDOUT_NOT_REGEX=re] [-DSTDERR_REGEX=re]
#         [-DSTDERR_NOT_REGEX=re]
#         [-DOUT_DIR=dir -DOUT_FILES=a.png|b.png] [-DNO_CARRIAGE_RETURN=ON]
#         -P run_cli.cmake -- COMMAND [ARG...]
#
# REQUIRE: files the test needs (real data). When one is missing the script
#   prints "HOROPTER_TEST_SKIPPED: ..." and ctest reports the test as skipped
#   (SKIP_REGULAR_EXPRESSION), so missing data never passes silently.
# EXPECT_EXIT: the exit status wanted (default 0); "nonzero" for any failure.
# STDOUT_REGEX / STDERR_REGEX: regular expressions the outputs must match.
# STDOUT_NOT_REGEX / STDERR_NOT_REGEX: regular expressions the outputs must not match.
# NO_CARRIAGE_RETURN: neither output may hold a '\r' (the outputs are pipes here,
#   not terminals, so no progress bar may rewrite its line into them).
# OUT_DIR: emptied before the run; OUT_FILES must then exist in it, non-empty.
# Lists use "|" as separator (a ";" would be split by add_test).

set(command "")
set(seen_separator FALSE)
math(EXPR last "${CMAKE_ARGC} - 1")
foreach(i RANGE ${last})
  if(seen_separator)
    list(APPEND command "${CMAKE_ARGV${i}}")
  elseif("${CMAKE_ARGV${i}}" STREQUAL "--")
    set(seen_separator TRUE)
  endif()
endforeach()
if(NOT command)
  message(FATAL_ERROR "run_cli.cmake: no command after --")
endif()

if(DEFINED REQUIRE AND NOT REQUIRE STREQUAL "")
  string(REPLACE "|" ";" required "${REQUIRE}")
  foreach(file IN LISTS required)
    if(NOT EXISTS "${file}")
      message("HOROPTER_TEST_SKIPPED: test data not found: ${file} (the real data lives in "
              "../shared/data beside the repository; opencv-doc's examples in "
              "/usr/share/doc/opencv-doc/examples/data)")
      return()
    endif()
  endforeach()
endif()

if(DEFINED OUT_DIR)
  file(REMOVE_RECURSE "${OUT_DIR}")
endif()

string(REPLACE ";" " " shown "${command}")
message("running: ${shown}")
execute_process(COMMAND ${command}
  RESULT_VARIABLE status
  OUTPUT_VARIABLE out
  ERROR_VARIABLE err)
message("exit status: ${status}\n--- stdout ---\n${out}--- stderr ---\n${err}--------------")

set(problems "")
if(NOT DEFINED EXPECT_EXIT)
  set(EXPECT_EXIT 0)
endif()
if(NOT status MATCHES "^[0-9]+$")
  string(APPEND problems "\n  the command did not exit normally: ${status}")
elseif(EXPECT_EXIT STREQUAL "nonzero")
  if(status EQUAL 0)
    string(APPEND problems "\n  exit status 0, expected a failure")
  endif()
elseif(NOT status EQUAL EXPECT_EXIT)
  string(APPEND problems "\n  exit status ${status}, expected ${EXPECT_EXIT}")
endif()
if(DEFINED STDOUT_REGEX AND NOT out MATCHES "${STDOUT_REGEX}")
  string(APPEND problems "\n  stdout does not match: ${STDOUT_REGEX}")
endif()
if(DEFINED STDOUT_NOT_REGEX AND out MATCHES "${STDOUT_NOT_REGEX}")
  string(APPEND problems "\n  stdout matches what it must not: ${STDOUT_NOT_REGEX}")
endif()
if(DEFINED STDERR_REGEX AND NOT err MATCHES "${STDERR_REGEX}")
  string(APPEND problems "\n  stderr does not match: ${STDERR_REGEX}")
endif()
if(DEFINED STDERR_NOT_REGEX AND err MATCHES "${STDERR_NOT_REGEX}")
  string(APPEND problems "\n  stderr matches what it must not: ${STDERR_NOT_REGEX}")
endif()
if(NO_CARRIAGE_RETURN)
  string(FIND "${out}${err}" "\r" carriage_return)
  if(NOT carriage_return EQUAL -1)
    string(APPEND problems "\n  the output holds a carriage return (a progress bar outside a terminal)")
  endif()
endif()
if(DEFINED OUT_FILES)
  string(REPLACE "|" ";" wanted "${OUT_FILES}")
  foreach(file IN LISTS wanted)
    set(path "${OUT_DIR}/${file}")
    if(NOT EXISTS "${path}")
      string(APPEND problems "\n  ${path} was not written")
    else()
      file(SIZE "${path}" size)
      if(size EQUAL 0)
        string(APPEND problems "\n  ${path} is empty")
      elseif(file MATCHES "\\.png$")
        file(READ "${path}" signature LIMIT 8 HEX)
        if(NOT signature STREQUAL "89504e470d0a1a0a")
          string(APPEND problems "\n  ${path} is not a PNG file")
        endif()
      endif()
    endif()
  endforeach()
endif()
if(problems)
  message(FATAL_ERROR "FAILED:${problems}")
endif()
message("PASSED")
