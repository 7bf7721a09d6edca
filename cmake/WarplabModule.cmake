# warplab_module(NAME [PUBLIC deps...] [PRIVATE deps...] SOURCES src...)
#
# One module = one folder = one static library `warplab_NAME`. Its public headers live in
# NAME/include/NAME/ and are the only include root it exports, so `#include "NAME/x.h"` works
# exactly in the targets that link it; its sources and private headers live in NAME/src/
# (found as "x.h" from inside the module). Dependencies are PRIVATE unless a public header
# needs them, so the arrows of docs/architecture.md hold by construction: a module that
# does not link another cannot include its headers (tests/modules/ proves it).
#
# Also defines `warplab_NAME_internal`, an interface target that adds NAME/src to the include
# path: for the module's own tests, which may look inside it, and for nothing else.
function(warplab_module name)
  cmake_parse_arguments(M "" "" "SOURCES;PUBLIC;PRIVATE" ${ARGN})
  add_library(warplab_${name} STATIC ${M_SOURCES})
  target_include_directories(warplab_${name}
    PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/include
    PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/src)
  target_link_libraries(warplab_${name} PUBLIC ${M_PUBLIC} PRIVATE ${M_PRIVATE})
  add_library(warplab_${name}_internal INTERFACE)
  target_include_directories(warplab_${name}_internal INTERFACE ${CMAKE_CURRENT_SOURCE_DIR}/src)
  target_link_libraries(warplab_${name}_internal INTERFACE warplab_${name} ${M_PRIVATE})
endfunction()
