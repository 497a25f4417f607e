# The installable SDK: `cmake --install build --prefix P` gives
#   P/bin/plab                      the CLI (finds its plug-ins relative to itself)
#   P/lib/libplab_core.so           the kernel plab runs on
#   P/lib/plab/plugins/plab_*.so    the built-in plug-ins
#   P/include/plab/*.h*             the public plug-in API (all a plug-in includes)
#   P/lib/cmake/ParticleLab/        find_package(ParticleLab): plab::api,
#                                   plab_add_contact_model(), PLAB_EXECUTABLE
include(CMakePackageConfigHelpers)

set(PLAB_INSTALL_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/ParticleLab)

install(DIRECTORY ${PROJECT_SOURCE_DIR}/core/include/plab DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS plab_api EXPORT ParticleLabTargets)
install(TARGETS plab_core LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS plab RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(EXPORT ParticleLabTargets NAMESPACE plab:: DESTINATION ${PLAB_INSTALL_CMAKE_DIR})

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/ParticleLabConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/ParticleLabConfig.cmake
  INSTALL_DESTINATION ${PLAB_INSTALL_CMAKE_DIR}
  PATH_VARS CMAKE_INSTALL_BINDIR PLAB_INSTALL_PLUGIN_DIR CMAKE_INSTALL_INCLUDEDIR)
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/ParticleLabConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/ParticleLabConfig.cmake
  ${CMAKE_CURRENT_BINARY_DIR}/ParticleLabConfigVersion.cmake
  ${PROJECT_SOURCE_DIR}/cmake/PlabPlugin.cmake
  DESTINATION ${PLAB_INSTALL_CMAKE_DIR})
