# GMP's C++ interface (Debian libgmp-dev: gmpxx.h, libgmpxx, libgmp), for exact rationals in the
# CLI's `ccd-queries` (reading rational CSV files) and in the CCD tests' exact truth. Never linked
# into the core library. Defines the imported target antcd_gmpxx when found.
if(NOT TARGET antcd_gmpxx)
  find_path(ANTCD_GMPXX_INCLUDE_DIR gmpxx.h)
  find_library(ANTCD_GMPXX_LIBRARY gmpxx)
  find_library(ANTCD_GMP_LIBRARY gmp)
  if(ANTCD_GMPXX_INCLUDE_DIR AND ANTCD_GMPXX_LIBRARY AND ANTCD_GMP_LIBRARY)
    add_library(antcd_gmpxx INTERFACE IMPORTED)
    target_include_directories(antcd_gmpxx INTERFACE ${ANTCD_GMPXX_INCLUDE_DIR})
    target_link_libraries(antcd_gmpxx INTERFACE ${ANTCD_GMPXX_LIBRARY} ${ANTCD_GMP_LIBRARY})
  else()
    message(STATUS "GMP (gmpxx) not found: `antcd ccd-queries` reports that, CCD truth tests not built")
  endif()
endif()
