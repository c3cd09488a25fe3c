# All dependencies come from Debian packages (scripts/install-deps.sh installs them).
# cmake/ManifoldSplinesConfig.cmake.in finds the same ones for a consumer of the installed
# package: a change here goes there too.

find_package(Eigen3 3.4 REQUIRED NO_MODULE)

# OpenMesh ships no version file; it must be found before CGAL, whose FindOpenMesh would win.
find_package(OpenMesh CONFIG REQUIRED)

find_package(CGAL 5.5 REQUIRED)
find_package(TinyGLTF 2.7 CONFIG REQUIRED)
find_package(nlohmann_json 3 REQUIRED)
find_package(ZLIB REQUIRED)
find_package(Threads REQUIRED)

include("${CMAKE_CURRENT_LIST_DIR}/ImportedLibraries.cmake")
