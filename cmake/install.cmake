# Installation: the library as a CMake package, usable with find_package(ipstep).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

install(TARGETS ipstep ipstep_scene EXPORT ipstepTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS ipstep_app RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
foreach(dir contact core energies integrators mesh problems sim solver io)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${dir}/ DESTINATION include/ipstep/${dir}
    FILES_MATCHING PATTERN "*.h")
endforeach()
install(EXPORT ipstepTargets NAMESPACE ipstep:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/ipstep)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/ipstepConfig.cmake.in
  ${PROJECT_BINARY_DIR}/ipstepConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/ipstep)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/ipstepConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/ipstepConfig.cmake ${PROJECT_BINARY_DIR}/ipstepConfigVersion.cmake
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/ipstep)
