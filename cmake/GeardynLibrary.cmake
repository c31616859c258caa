# geardyn_add_library(<name> ALIAS <alias> [PUBLIC_LIBS ...] [PRIVATE_LIBS ...]
#                     [UNINSTRUMENTED <src>...])
# One library per top-level area. Sources are every .cpp below src/ (CONFIGURE_DEPENDS, so new
# files are picked up); headers live in include/geardyn/<area>/ and are installed as they are.
#
# In the sanitized twin (cmake/sanitized_twin/, GEARDYN_TWIN_SUFFIX = _sanitized) the same call
# makes <name>_sanitized and <alias>_sanitized, links the twins of geardyn:: libraries and installs
# nothing. UNINSTRUMENTED sources (paths below src/) are compiled once, in the object library
# <name>_uninstrumented, whose objects both the library and its twin hold: third-party template
# code that the sanitizers need not check (Eigen's decompositions: 133 s of sanitized compile).
function(geardyn_add_library name)
  cmake_parse_arguments(ARG "" "ALIAS" "PUBLIC_LIBS;PRIVATE_LIBS;UNINSTRUMENTED" ${ARGN})
  set(suffix "${GEARDYN_TWIN_SUFFIX}")
  file(GLOB_RECURSE sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/src/*.cpp)
  set(uninstrumented "")
  foreach(src IN LISTS ARG_UNINSTRUMENTED)
    list(APPEND uninstrumented ${CMAKE_CURRENT_SOURCE_DIR}/src/${src})
  endforeach()
  if(uninstrumented)
    list(REMOVE_ITEM sources ${uninstrumented})
  endif()
  set(public_libs "")
  foreach(lib IN LISTS ARG_PUBLIC_LIBS)
    if(lib MATCHES "^geardyn::")
      string(APPEND lib "${suffix}")
    endif()
    list(APPEND public_libs ${lib})
  endforeach()
  add_library(${name}${suffix} STATIC ${sources})
  add_library(${ARG_ALIAS}${suffix} ALIAS ${name}${suffix})
  target_include_directories(${name}${suffix}
                             PUBLIC $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
                                    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>
                             PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/src)
  target_compile_features(${name}${suffix} PUBLIC cxx_std_20)
  target_link_libraries(${name}${suffix} PUBLIC ${public_libs}
                                         PRIVATE ${ARG_PRIVATE_LIBS} geardyn_warnings)
  geardyn_precompile_headers(${name}${suffix} ${GEARDYN_PCH_LIBRARY_HEADERS})
  if(uninstrumented)
    if(NOT suffix)
      add_library(${name}_uninstrumented OBJECT ${uninstrumented})
      target_include_directories(${name}_uninstrumented
                                 PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/include
                                         ${CMAKE_CURRENT_SOURCE_DIR}/src)
      target_link_libraries(${name}_uninstrumented PRIVATE ${ARG_PUBLIC_LIBS} geardyn_warnings)
    endif()
    target_sources(${name}${suffix} PRIVATE $<TARGET_OBJECTS:${name}_uninstrumented>)
  endif()
  if(suffix)
    return()
  endif()
  string(REPLACE "geardyn::" "" export_name ${ARG_ALIAS})
  set_target_properties(${name} PROPERTIES EXPORT_NAME ${export_name})
  install(TARGETS ${name} EXPORT geardynTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
  install(DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endfunction()
