# Embeds text files under configs/ and reports/ into the library as C++ string tables,
# so that `phasmid demo` and `phasmid report` work without the source tree.
file(GLOB_RECURSE PHASMID_EMBED_FILES CONFIGURE_DEPENDS
  ${CMAKE_SOURCE_DIR}/configs/*.toml
  ${CMAKE_SOURCE_DIR}/reports/*.html ${CMAKE_SOURCE_DIR}/reports/*.js ${CMAKE_SOURCE_DIR}/reports/*.css
  ${CMAKE_SOURCE_DIR}/datasets/simroach2/*.csv)
set(_embed_cpp ${CMAKE_BINARY_DIR}/generated/phasmid_embedded.cpp)
set(_embed_list ${CMAKE_BINARY_DIR}/generated/embedded_files.txt)
string(REPLACE ";" "\n" _embed_lines "${PHASMID_EMBED_FILES}")
file(WRITE ${_embed_list} "${_embed_lines}")
add_custom_command(
  OUTPUT ${_embed_cpp}
  COMMAND ${CMAKE_COMMAND} -DOUT=${_embed_cpp} -DROOT=${CMAKE_SOURCE_DIR} -DLIST=${_embed_list}
          -P ${CMAKE_SOURCE_DIR}/cmake/EmbedFiles.cmake
  DEPENDS ${PHASMID_EMBED_FILES} ${_embed_list} ${CMAKE_SOURCE_DIR}/cmake/EmbedFiles.cmake
  COMMENT "Embedding configs and report assets")
target_sources(phasmid_lib PRIVATE ${_embed_cpp})
