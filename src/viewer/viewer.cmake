# The viewer module's build. Embeds every file of src/viewer/assets/ into the library as bytes (a generated .cpp defining
# lfcam::viewer::findAsset), so the lfcam binary serves and exports its page without files.
file(GLOB LFCAM_VIEWER_ASSETS CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/viewer/assets/*)
set(LFCAM_VIEWER_ASSETS_CPP ${PROJECT_BINARY_DIR}/generated/viewer_assets.cpp)
add_custom_command(
  OUTPUT ${LFCAM_VIEWER_ASSETS_CPP}
  COMMAND ${CMAKE_COMMAND} -DASSET_DIR=${PROJECT_SOURCE_DIR}/src/viewer/assets -DOUTPUT=${LFCAM_VIEWER_ASSETS_CPP}
          -P ${PROJECT_SOURCE_DIR}/src/viewer/embed_assets_script.cmake
  DEPENDS ${LFCAM_VIEWER_ASSETS} ${PROJECT_SOURCE_DIR}/src/viewer/embed_assets_script.cmake
  COMMENT "Embedding the viewer's page")
target_sources(lfcam_viewer PRIVATE ${LFCAM_VIEWER_ASSETS_CPP})

# cpp-httplib (Debian builds it as a library whose ABI depends on its definitions): only the
# server's source is compiled with its flags, and the library is linked.
set_source_files_properties(${PROJECT_SOURCE_DIR}/src/viewer/viewer_server.cpp PROPERTIES
  COMPILE_OPTIONS "${HTTPLIB_CFLAGS}")
target_link_libraries(lfcam_viewer PRIVATE ${HTTPLIB_LINK_LIBRARIES})
