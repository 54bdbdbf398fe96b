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

# pkg-config beside the CMake package: lib/pkgconfig/bouncer.pc (cmake/bouncer.pc.in), its
# prefix relative to its own place. The libraries are static: their dependencies are in
# Requires and Libs, not the .private fields, so that `pkg-config --libs bouncer` links.
file(RELATIVE_PATH BOUNCER_PC_TO_PREFIX /${CMAKE_INSTALL_LIBDIR}/pkgconfig /)
string(REGEX REPLACE "/$" "" BOUNCER_PC_TO_PREFIX "${BOUNCER_PC_TO_PREFIX}")
string(REPLACE "SHELL:" "" BOUNCER_PC_QUADMATH "${BOUNCER_QUADMATH_INCLUDE_FLAGS}")
string(JOIN " " BOUNCER_PC_CFLAGS ${BOUNCER_FP_FLAGS} ${BOUNCER_PC_QUADMATH})
set(BOUNCER_PC_LIBS -l${QUADMATH_LIBRARY})
if(BOUNCER_SANITIZE)
  string(APPEND BOUNCER_PC_CFLAGS " -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer")
  string(APPEND BOUNCER_PC_LIBS " -fsanitize=address,undefined")
endif()
configure_file(cmake/bouncer.pc.in ${CMAKE_CURRENT_BINARY_DIR}/bouncer.pc @ONLY)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/bouncer.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

# What `bouncer reproduce` needs beyond bin/bouncer: the proof programs (proofs/CMakeLists.txt,
# libexec/bouncer/). The paper's manifest and the scenes are compiled into the library
# (workflow/paper.hpp), so an install reproduces from any directory and `--scene NAME` finds
# them; the files go to share/bouncer/ as well, to read, copy and edit (--scene PATH,
# reproduce --manifest PATH).
install(DIRECTORY data/scenes DESTINATION ${CMAKE_INSTALL_DATADIR}/bouncer FILES_MATCHING PATTERN "*.toml")
install(FILES data/paper/manifest.toml DESTINATION ${CMAKE_INSTALL_DATADIR}/bouncer/paper)

# A Debian package: `cpack -G DEB` in a build directory (tools/setup package configures one
# for /usr). dpkg-shlibdeps finds the shared libraries the programs and the Python module
# link (MPFR, GMP, qd, Cairo, libpng, ...); python3 and python3-numpy are the module's.
set(CPACK_PACKAGE_NAME bouncer)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_VENDOR "bouncer")
# The maintainer is the authors as CITATION.cff names them (the project publishes no address,
# so none is made up here).
set(CPACK_PACKAGE_CONTACT "The bouncer authors")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "Verified numerics for the piecewise linear bouncer (Langer & Miller 2014)")
# What a C++ developer installs to build against the installed library (find_package(bouncer)
# or pkg-config bouncer; cmake/bouncerConfig.cmake.in and bouncer.pc.in name the same): the
# headers and static libraries are in this package, their dependencies' headers are not.
set(BOUNCER_DEV_PACKAGES "g++, cmake | pkg-config, libboost-dev, libgmp-dev, libmpfr-dev, libmpfi-dev, libqd-dev, libflint-arb-dev, nlohmann-json3-dev, libtomlplusplus-dev, libpng-dev, libcairo2-dev, libfreetype-dev")
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "${BOUNCER_DEV_PACKAGES}")
string(REPLACE ", cmake | pkg-config" ", cmake or pkg-config" BOUNCER_DEV_PACKAGES_TEXT "${BOUNCER_DEV_PACKAGES}")
string(REPLACE "," "" BOUNCER_DEV_PACKAGES_TEXT "${BOUNCER_DEV_PACKAGES_TEXT}")
# (cpack takes the Description's first line from the summary above: this is the rest.)
set(CPACK_DEBIAN_PACKAGE_DESCRIPTION "The exact impact map of a particle bouncing on a wall that moves as a triangle wave, in
double, long double, double-double, quad, MPFR and interval arithmetic, with certified
answers (sticking, periodic orbits, basins) and the figures of the paper. Installs the
bouncer command, the proof programs bouncer reproduce runs (libexec/bouncer), the scenes
and the paper's manifest (share/bouncer), the Python module, and the C++ library's headers
and static libraries with a CMake package and a pkg-config file.
To build C++ programs against the library (find_package(bouncer) or pkg-config bouncer),
install as well (the Suggests):
${BOUNCER_DEV_PACKAGES_TEXT}.")
set(CPACK_RESOURCE_FILE_LICENSE ${CMAKE_CURRENT_SOURCE_DIR}/LICENSE)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # bouncer_VERSION_ARCH.deb
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "python3, python3-numpy")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_GENERATOR DEB)
include(CPack)
