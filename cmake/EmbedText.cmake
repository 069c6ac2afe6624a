# nx_embed_text(<target> <symbol> <file>): compiles the text of <file> into <target> as
#   extern const char* const <symbol>;
# The data files stay readable CSV in the source tree and need no file access at run time.
function(nx_embed_text target symbol file)
  set(source "${CMAKE_CURRENT_SOURCE_DIR}/${file}")
  set(generated "${CMAKE_CURRENT_BINARY_DIR}/embedded_${symbol}.cpp")
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS "${source}")
  file(READ "${source}" content)
  file(WRITE "${generated}.tmp"
       "// Generated from ${file} by cmake/EmbedText.cmake; do not edit.\n"
       "namespace nx { extern const char* const ${symbol};\n"
       "const char* const ${symbol} = R\"nxdata(${content})nxdata\"; }\n")
  configure_file("${generated}.tmp" "${generated}" COPYONLY)
  target_sources(${target} PRIVATE "${generated}")
endfunction()
