# Embeds text files under configs/ and reports/ into the library as C++ string tables,
# so that `phasmid demo` and `phasmid report` work without the source tree.
file(GLOB_RECURSE PHASMID_EMBED_FILES CONFIGURE_DEPENDS
  ${CMAKE_SOURCE_DIR}/configs/*.toml
  ${CMAKE_SOURCE_DIR}/reports/*.html ${CMAKE_SOURCE_DIR}/reports/*.js ${CMAKE_SOURCE_DIR}/reports/*.css)
set(_embed_cpp ${CMAKE_BINARY_DIR}/generated/phasmid_embedded.cpp)
add_custom_command(
  OUTPUT ${_embed_cpp}
  COMMAND ${CMAKE_COMMAND} -DOUT=${_embed_cpp} -DROOT=${CMAKE_SOURCE_DIR} "-DFILES=${PHASMID_EMBED_FILES}"
          -P ${CMAKE_SOURCE_DIR}/cmake/EmbedFiles.cmake
  DEPENDS ${PHASMID_EMBED_FILES} ${CMAKE_SOURCE_DIR}/cmake/EmbedFiles.cmake
  COMMENT "Embedding configs and report assets"
  VERBATIM)  # without it the ';'-separated FILES list is split by the shell once there are 2+ files
target_sources(phasmid_lib PRIVATE ${_embed_cpp})
