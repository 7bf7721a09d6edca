# Every tracked C++ source and header follows the root .clang-format (scripts/format.sh
# applies it). Lists the files that do not.
file(GLOB_RECURSE files RELATIVE "${SOURCE_DIR}" "${SOURCE_DIR}/*.cpp" "${SOURCE_DIR}/*.h")
set(unformatted "")
foreach(f IN LISTS files)
  if(f MATCHES "^(build|build-[^/]*|demo-out|bench-out|results)/")
    continue()
  endif()
  execute_process(COMMAND ${CLANG_FORMAT} --dry-run -Werror "${SOURCE_DIR}/${f}"
                  RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
  if(NOT rc EQUAL 0)
    string(APPEND unformatted "\n  ${f}")
  endif()
endforeach()
if(unformatted)
  message(FATAL_ERROR "not formatted as .clang-format says (run scripts/format.sh):${unformatted}")
endif()
