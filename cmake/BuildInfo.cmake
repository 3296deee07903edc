# What Clatter was built with, for `--version` and bank provenance: compiler, build type and the
# header versions are fixed at configure time; the git revision is re-read at every build. The
# HDF5 and MPI libraries are asked at run time instead (io/linked_libraries.cpp).

set(CLATTER_COMPILER "${CMAKE_CXX_COMPILER_ID} ${CMAKE_CXX_COMPILER_VERSION}")
set(CLATTER_BUILD_TYPE "${CMAKE_BUILD_TYPE}")
configure_file(${CMAKE_CURRENT_LIST_DIR}/build_info.cpp.in ${PROJECT_BINARY_DIR}/generated/build_info.cpp @ONLY)

add_custom_target(clatter_git_revision
  COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${PROJECT_SOURCE_DIR}
          -DOUTPUT=${PROJECT_BINARY_DIR}/generated/git_revision.cpp
          -P ${CMAKE_CURRENT_LIST_DIR}/GitRevision.cmake
  BYPRODUCTS ${PROJECT_BINARY_DIR}/generated/git_revision.cpp
  COMMENT "Reading git revision")
