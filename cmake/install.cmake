# Installation: the library as a CMake package, usable with find_package(ipstep).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

# ipstep::ipstep (the library: one target per folder, cmake/ipstep_library.cmake)
# and ipstep::flags (the programs as library calls, apps/programs.h, with their
# flags).
get_property(ipstep_libraries GLOBAL PROPERTY IPSTEP_LIBRARIES)
install(TARGETS ipstep ipstep_blas ${ipstep_libraries} ipstep_flags EXPORT ipstepTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS ipstep_app ipstep_compare ipstep_tune RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
if(TARGET ipstep_bench_lib)  # ipstep::bench (bench/bench_program.h: RunBench)
  install(TARGETS ipstep_bench_lib EXPORT ipstepTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
  install(TARGETS ipstep_bench RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  install(FILES ${PROJECT_SOURCE_DIR}/bench/bench_program.h ${PROJECT_SOURCE_DIR}/bench/bench_runner.h
                ${PROJECT_SOURCE_DIR}/bench/optimizer_spec.h
          DESTINATION include/ipstep/bench)
endif()
foreach(dir apps contact core energies geometry integrators mesh problems sim solver io)
  # problems/scene_parser.h is the scene loader's internal reader (namespace
  # internal), not an interface: not installed.
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${dir}/ DESTINATION include/ipstep/${dir}
    FILES_MATCHING PATTERN "*.h" PATTERN "scene_parser.h" EXCLUDE)
endforeach()
install(EXPORT ipstepTargets NAMESPACE ipstep:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/ipstep)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/ipstepConfig.cmake.in
  ${PROJECT_BINARY_DIR}/ipstepConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/ipstep)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/ipstepConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/ipstepConfig.cmake ${PROJECT_BINARY_DIR}/ipstepConfigVersion.cmake
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/ipstep)
