# Fails if HEADER includes, directly or through others, any of FORBIDDEN
# (file names, comma-separated). Run by ctest with the project's compiler:
#   cmake -DCXX=... -DINCLUDE_DIR=... -DHEADER=... -DFORBIDDEN=a.hpp,b.hpp -P header_layering.cmake
string(REPLACE "," ";" FORBIDDEN "${FORBIDDEN}")
execute_process(
  COMMAND ${CXX} -std=c++17 -I${INCLUDE_DIR} -x c++ -M ${HEADER}
  OUTPUT_VARIABLE deps ERROR_VARIABLE errors RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "header_layering: ${HEADER} does not compile on its own:\n${errors}")
endif()
set(found "")
foreach(name IN LISTS FORBIDDEN)
  string(REGEX MATCH "[^ \t\r\n]*/${name}" hit "${deps}")
  if(hit)
    list(APPEND found "${hit}")
  endif()
endforeach()
if(found)
  message(FATAL_ERROR "header_layering: ${HEADER} pulls in ${found}")
endif()
message(STATUS "header_layering: ${HEADER} includes none of ${FORBIDDEN}")
