# ipstep_library(<folder> SOURCES <files...> DEPENDS <targets...>)
#
# One static library per source folder, target ipstep_<folder>, linked to the
# folders below it only (the layer order in the top-level CMakeLists.txt):
# code that calls upwards leaves an undefined symbol in the link of every
# program (static libraries resolve in dependency order), and
# tools/check_layers.py (ctest "layers") rejects upward #includes, which the
# linker cannot see in headers.
function(ipstep_library folder)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPENDS" ${ARGN})
  set(target ipstep_${folder})
  add_library(${target} STATIC ${ARG_SOURCES})
  add_library(ipstep::${target} ALIAS ${target})
  target_include_directories(${target} PUBLIC
    $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}>
    $<INSTALL_INTERFACE:include/ipstep>)
  target_compile_features(${target} PUBLIC cxx_std_17)
  # BUILD_INTERFACE: a static library's private link items end up in its
  # exported interface; the warning flags must not (ipstep_warnings is not
  # installed).
  target_link_libraries(${target} PUBLIC ${ARG_DEPENDS}
                        PRIVATE $<BUILD_INTERFACE:ipstep_warnings>)
  set_property(GLOBAL APPEND PROPERTY IPSTEP_LIBRARIES ${target})
endfunction()
