# Generates build_info.cpp with the version and the git commit, re-run on every
# build; the file is rewritten only when its content changes.
set(SPLAT_BUILD_INFO_CPP ${CMAKE_BINARY_DIR}/generated/build_info.cpp)
add_custom_target(splat_build_info_gen
  COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${CMAKE_SOURCE_DIR} -DOUTPUT=${SPLAT_BUILD_INFO_CPP}
          -DVERSION=${PROJECT_VERSION} -P ${CMAKE_SOURCE_DIR}/cmake/write_build_info.cmake
  BYPRODUCTS ${SPLAT_BUILD_INFO_CPP}
  COMMENT "Recording version and git commit")
