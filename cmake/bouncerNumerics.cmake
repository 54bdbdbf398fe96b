# Imported targets for the C numerics libraries, which ship no CMake package of their own
# (Debian: libgmp-dev, libmpfr-dev, libmpfi-dev, libqd-dev, libflint-arb-dev): bouncer::gmp,
# bouncer::gmpxx, bouncer::mpfr, bouncer::mpfi, bouncer::qd (QD, double-double exp/log for
# --precision dd), bouncer::flint and bouncer::arb (Arb, the second interval library that
# replays chaos certificates: verify/chaos_certificate.hpp). Used by the build and installed with the package config, so
# that an installed bouncer refers to these targets, never to the build machine's paths.
include(FindPackageHandleStandardArgs)
foreach(lib IN ITEMS gmp gmpxx mpfr mpfi qd flint arb)
  if(TARGET bouncer::${lib})
    continue()
  endif()
  set(header ${lib}.h)
  if(lib STREQUAL "gmpxx")
    set(header gmpxx.h)
  elseif(lib STREQUAL "qd")
    set(header qd/dd_real.h)
  elseif(lib STREQUAL "flint")
    set(header flint/flint.h)
  endif()
  set(libname ${lib})
  if(lib STREQUAL "arb")
    set(libname flint-arb)  # Debian's name for Arb's library
  endif()
  find_path(BOUNCER_${lib}_INCLUDE_DIR ${header})
  find_library(BOUNCER_${lib}_LIBRARY ${libname})
  find_package_handle_standard_args(bouncer_${lib} REQUIRED_VARS BOUNCER_${lib}_LIBRARY BOUNCER_${lib}_INCLUDE_DIR
                                    NAME_MISMATCHED)
  if(NOT bouncer_${lib}_FOUND)
    set(pkg libgmp-dev)
    if(lib MATCHES "^(mpf|qd|flint)")
      set(pkg lib${lib}-dev)
    elseif(lib STREQUAL "arb")
      set(pkg libflint-arb-dev)
    endif()
    message(FATAL_ERROR "bouncer: library ${lib} not found: install the Debian package '${pkg}' (apt-get install ${pkg})")
  endif()
  add_library(bouncer::${lib} UNKNOWN IMPORTED)
  set_target_properties(bouncer::${lib} PROPERTIES IMPORTED_LOCATION "${BOUNCER_${lib}_LIBRARY}"
                        INTERFACE_INCLUDE_DIRECTORIES "${BOUNCER_${lib}_INCLUDE_DIR}")
endforeach()
set_property(TARGET bouncer::gmpxx APPEND PROPERTY INTERFACE_LINK_LIBRARIES bouncer::gmp)
set_property(TARGET bouncer::mpfr APPEND PROPERTY INTERFACE_LINK_LIBRARIES bouncer::gmp)
set_property(TARGET bouncer::mpfi APPEND PROPERTY INTERFACE_LINK_LIBRARIES bouncer::mpfr)
set_property(TARGET bouncer::flint APPEND PROPERTY INTERFACE_LINK_LIBRARIES bouncer::mpfr)
set_property(TARGET bouncer::arb APPEND PROPERTY INTERFACE_LINK_LIBRARIES bouncer::flint)
