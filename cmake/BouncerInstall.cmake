# cmake --install: the library, its headers and a package config, so that another CMake
# project can use `find_package(bouncer)` and link `bouncer::bouncer`.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)
# Two export sets, one per library target: a consumer of bouncer::numerics alone
# (find_package(bouncer COMPONENTS numerics)) loads no I/O dependency (Cairo, libpng, ...).
install(TARGETS bouncer_numerics EXPORT bouncerNumericsTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS bouncer EXPORT bouncerTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(DIRECTORY lib/include/bouncer DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT bouncerNumericsTargets NAMESPACE bouncer:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/bouncer)
install(EXPORT bouncerTargets NAMESPACE bouncer:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/bouncer)
configure_package_config_file(cmake/bouncerConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/bouncerConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/bouncer)
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/bouncerConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/bouncerConfig.cmake ${CMAKE_CURRENT_BINARY_DIR}/bouncerConfigVersion.cmake
  ${CMAKE_CURRENT_SOURCE_DIR}/cmake/bouncerNumerics.cmake
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/bouncer)
# The licence, how to cite and what changed, beside the library (share/doc/bouncer).
install(FILES LICENSE CITATION.cff CHANGELOG.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
