# splat_embed_text(OUT_CPP FUNCTION FILES...)
# Generates OUT_CPP, which defines `std::span<const EmbeddedText> FUNCTION()`
# holding each file's text under its name up to the first dot. The binary then
# carries its schemas and material library and runs from any directory.
function(splat_embed_text out_cpp function_name)
  set(files ${ARGN})
  string(REPLACE ";" "|" files_arg "${files}")
  add_custom_command(OUTPUT ${out_cpp}
    COMMAND ${CMAKE_COMMAND} -DOUTPUT=${out_cpp} -DFUNCTION=${function_name}
            -DFILES=${files_arg} -P ${CMAKE_SOURCE_DIR}/cmake/write_embed.cmake
    DEPENDS ${files} ${CMAKE_SOURCE_DIR}/cmake/write_embed.cmake
    COMMENT "Embedding texts for ${function_name}()"
    VERBATIM)
endfunction()
