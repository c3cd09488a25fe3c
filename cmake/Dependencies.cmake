# All dependencies come from Debian packages (scripts/install-deps.sh installs them).

find_package(Eigen3 3.4 REQUIRED NO_MODULE)

# OpenMesh ships no version file; it must be found before CGAL, whose FindOpenMesh would win.
find_package(OpenMesh CONFIG REQUIRED)

find_package(CGAL 5.5 REQUIRED)
find_package(TinyGLTF 2.7 CONFIG REQUIRED)
find_package(nlohmann_json 3 REQUIRED)
find_package(ZLIB REQUIRED)
find_package(Threads REQUIRED)

# OpenSubdiv's CMake config imports a static library Debian does not ship: find it by hand.
find_path(OPENSUBDIV_INCLUDE_DIR opensubdiv/far/topologyRefiner.h REQUIRED)
find_library(OPENSUBDIV_CPU_LIBRARY osdCPU REQUIRED)
add_library(msp_opensubdiv INTERFACE IMPORTED)
target_include_directories(msp_opensubdiv INTERFACE "${OPENSUBDIV_INCLUDE_DIR}")
target_link_libraries(msp_opensubdiv INTERFACE "${OPENSUBDIV_CPU_LIBRARY}")

# CHOLMOD (SuiteSparse) through Eigen's CholmodSupport module.
find_path(CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse REQUIRED)
find_library(CHOLMOD_LIBRARY cholmod REQUIRED)
add_library(msp_cholmod INTERFACE IMPORTED)
target_include_directories(msp_cholmod INTERFACE "${CHOLMOD_INCLUDE_DIR}")
target_link_libraries(msp_cholmod INTERFACE "${CHOLMOD_LIBRARY}")
