# clatter_embed_text(FILE HEADER FUNCTION OUT): a text file of the source tree (a built-in table
# or config) compiled in as a raw string, returned by `const std::string& clatter::FUNCTION()`
# (declared in HEADER), so no binary depends on its working directory. Generated at configure
# time into OUT; a change to FILE re-runs the configure step, which regenerates it.
function(clatter_embed_text file header function out)
  file(READ ${file} CLATTER_EMBED_TEXT)
  string(FIND "${CLATTER_EMBED_TEXT}" ")clatter_toml\"" delimiter_at)
  if(NOT delimiter_at EQUAL -1)
    message(FATAL_ERROR "${file} contains the raw-string delimiter )clatter_toml\"")
  endif()
  file(RELATIVE_PATH CLATTER_EMBED_FILE ${PROJECT_SOURCE_DIR} ${file})
  set(CLATTER_EMBED_HEADER ${header})
  set(CLATTER_EMBED_FUNCTION ${function})
  configure_file(${PROJECT_SOURCE_DIR}/cmake/embedded_text.cpp.in ${out} @ONLY)
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${file})
endfunction()
