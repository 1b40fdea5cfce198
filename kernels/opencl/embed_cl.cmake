# Turns one OpenCL C file into a C++ source holding it as a raw string, so the
# library carries its kernels and reads nothing from disk at run time.
# Usage: cmake -DINPUT=file.cl -DOUTPUT=file.cpp -DNAME=identifier -P embed_cl.cmake
file(READ "${INPUT}" body)
string(FIND "${body}" ")HOROPTER_CL\"" clash)
if(NOT clash EQUAL -1)
  message(FATAL_ERROR "${INPUT} contains the raw-string delimiter )HOROPTER_CL\"")
endif()
get_filename_component(file_name "${INPUT}" NAME)
file(WRITE "${OUTPUT}.tmp"
  "// Generated at build time from ${file_name} by embed_cl.cmake: do not edit.\n"
  "#include \"opencl/cl_sources.hpp\"\n\n"
  "namespace horopter::opencl::sources {\n"
  "const char* const ${NAME} = R\"HOROPTER_CL(${body})HOROPTER_CL\";\n"
  "}  // namespace horopter::opencl::sources\n")
# Touch the output only when it changed, so nothing recompiles needlessly.
file(COPY_FILE "${OUTPUT}.tmp" "${OUTPUT}" ONLY_IF_DIFFERENT)
file(REMOVE "${OUTPUT}.tmp")
