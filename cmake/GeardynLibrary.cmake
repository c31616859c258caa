# geardyn_add_library(<name> ALIAS <alias> [PUBLIC_LIBS ...] [PRIVATE_LIBS ...])
# One library per top-level area. Sources are every .cpp below src/ (CONFIGURE_DEPENDS, so new
# files are picked up); headers live in include/geardyn/<area>/ and are installed as they are.
function(geardyn_add_library name)
  cmake_parse_arguments(ARG "" "ALIAS" "PUBLIC_LIBS;PRIVATE_LIBS" ${ARGN})
  file(GLOB_RECURSE sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/src/*.cpp)
  add_library(${name} STATIC ${sources})
  add_library(${ARG_ALIAS} ALIAS ${name})
  target_include_directories(${name} PUBLIC $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
                                            $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>
                                     PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/src)
  target_compile_features(${name} PUBLIC cxx_std_20)
  target_link_libraries(${name} PUBLIC ${ARG_PUBLIC_LIBS} PRIVATE ${ARG_PRIVATE_LIBS} geardyn_warnings)
  geardyn_precompile_headers(${name} ${GEARDYN_PCH_LIBRARY_HEADERS})
  string(REPLACE "geardyn::" "" export_name ${ARG_ALIAS})
  set_target_properties(${name} PROPERTIES EXPORT_NAME ${export_name})
  install(TARGETS ${name} EXPORT geardynTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
  install(DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endfunction()
