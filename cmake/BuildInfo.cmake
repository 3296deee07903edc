# Versions of what Clatter was built against, for `--version` and bank provenance.
# Library versions are fixed at configure time; the git revision is re-read at every build.

execute_process(COMMAND ${MPIEXEC_EXECUTABLE} --version OUTPUT_VARIABLE _mpiexec_version
                ERROR_QUIET OUTPUT_STRIP_TRAILING_WHITESPACE)
string(REGEX MATCH "^[^\n]*" CLATTER_MPI_LIBRARY "${_mpiexec_version}")
if(NOT CLATTER_MPI_LIBRARY)
  set(CLATTER_MPI_LIBRARY "MPI ${MPI_CXX_VERSION}")
endif()
set(CLATTER_COMPILER "${CMAKE_CXX_COMPILER_ID} ${CMAKE_CXX_COMPILER_VERSION}")
set(CLATTER_BUILD_TYPE "${CMAKE_BUILD_TYPE}")
configure_file(${CMAKE_CURRENT_LIST_DIR}/build_info.cpp.in ${PROJECT_BINARY_DIR}/generated/build_info.cpp @ONLY)

add_custom_target(clatter_git_revision
  COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${PROJECT_SOURCE_DIR}
          -DOUTPUT=${PROJECT_BINARY_DIR}/generated/git_revision.cpp
          -P ${CMAKE_CURRENT_LIST_DIR}/GitRevision.cmake
  BYPRODUCTS ${PROJECT_BINARY_DIR}/generated/git_revision.cpp
  COMMENT "Reading git revision")
