# prefetch_codegen.cmake — ctest script (cmake -P): compiles prefetch_probe.cpp to assembly with
# the project's compiler at -O3 and fails unless the probe function still issues prefetches.
# Arguments: -DCXX=compiler -DSOURCE_DIR=repository root -DOUT=assembly file to write.
execute_process(
  COMMAND ${CXX} -std=c++20 -O3 -DNDEBUG -I${SOURCE_DIR}/src -S -o ${OUT}
          ${SOURCE_DIR}/tests/parallel/prefetch_probe.cpp
  RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "prefetch_probe.cpp did not compile: ${err}")
endif()
file(READ ${OUT} asm)
set(label "caustica_prefetch_probe:")
string(FIND "${asm}" "${label}" begin)
if(begin EQUAL -1)
  message(FATAL_ERROR "no caustica_prefetch_probe in ${OUT}")
endif()
string(LENGTH "${label}" labelLength)
math(EXPR begin "${begin} + ${labelLength}")  # past the label
string(SUBSTRING "${asm}" ${begin} -1 body)
string(FIND "${body}" ".cfi_endproc" end)
if(end GREATER 0)
  string(SUBSTRING "${body}" 0 ${end} body)
endif()
string(REGEX MATCHALL "[ \t]prefetch[a-z0-9]*[ \t]" found "${body}")
list(LENGTH found count)
if(count LESS 3)  # the three vertex positions at least
  message(FATAL_ERROR "caustica_prefetch_probe issues ${count} prefetches (expected >= 3): the "
                      "compiler dropped the hit prefetches (see parallel/prefetch.h)\n${body}")
endif()
message(STATUS "caustica_prefetch_probe issues ${count} prefetches")
