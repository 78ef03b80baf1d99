# Embeds text files under configs/ and reports/ into the library as C++ string tables,
# so that `phasmid demo` and `phasmid report` work without the source tree.
file(GLOB_RECURSE PHASMID_EMBED_FILES CONFIGURE_DEPENDS
  ${CMAKE_SOURCE_DIR}/configs/*.toml
  ${CMAKE_SOURCE_DIR}/reports/*.html ${CMAKE_SOURCE_DIR}/reports/*.js ${CMAKE_SOURCE_DIR}/reports/*.css)
set(_embed_cpp ${CMAKE_BINARY_DIR}/generated/phasmid_embedded.cpp)
# A ";" inside a custom command reaches the shell as a command separator: pass the list "|"-joined.
string(REPLACE ";" "|" _embed_list "${PHASMID_EMBED_FILES}")
add_custom_command(
  OUTPUT ${_embed_cpp}
  COMMAND ${CMAKE_COMMAND} -DOUT=${_embed_cpp} -DROOT=${CMAKE_SOURCE_DIR} "-DFILES=${_embed_list}"
          -P ${CMAKE_SOURCE_DIR}/cmake/EmbedFiles.cmake
  DEPENDS ${PHASMID_EMBED_FILES} ${CMAKE_SOURCE_DIR}/cmake/EmbedFiles.cmake
  COMMENT "Embedding configs and report assets"
  VERBATIM)
target_sources(phasmid_lib PRIVATE ${_embed_cpp})
