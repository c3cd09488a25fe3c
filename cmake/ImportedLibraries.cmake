# The two libraries without a usable CMake package, as INTERFACE IMPORTED targets. Included by
# the build (Dependencies.cmake) and by the installed ManifoldSplinesConfig.cmake, whose static
# libraries link them, so both define them the same way.

# OpenSubdiv's CMake config imports a static library Debian does not ship: find it by hand.
if(NOT TARGET msp_opensubdiv)
  find_path(OPENSUBDIV_INCLUDE_DIR opensubdiv/far/topologyRefiner.h REQUIRED)
  find_library(OPENSUBDIV_CPU_LIBRARY osdCPU REQUIRED)
  add_library(msp_opensubdiv INTERFACE IMPORTED)
  target_include_directories(msp_opensubdiv INTERFACE "${OPENSUBDIV_INCLUDE_DIR}")
  target_link_libraries(msp_opensubdiv INTERFACE "${OPENSUBDIV_CPU_LIBRARY}")
endif()

# CHOLMOD (SuiteSparse) through Eigen's CholmodSupport module.
if(NOT TARGET msp_cholmod)
  find_path(CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse REQUIRED)
  find_library(CHOLMOD_LIBRARY cholmod REQUIRED)
  add_library(msp_cholmod INTERFACE IMPORTED)
  target_include_directories(msp_cholmod INTERFACE "${CHOLMOD_INCLUDE_DIR}")
  target_link_libraries(msp_cholmod INTERFACE "${CHOLMOD_LIBRARY}")
endif()
