# The installed CMake package: `cmake --install build --prefix P` puts the public headers under
# P/include/ManifoldSplines, the static libraries under P/lib and ManifoldSplinesConfig.cmake
# (with its version file and the exported targets ManifoldSplines::ricci, ::spline, ::io) under
# P/lib/cmake/ManifoldSplines, so an outside project writes
#   find_package(ManifoldSplines CONFIG REQUIRED)
#   target_link_libraries(app PRIVATE ManifoldSplines::spline ManifoldSplines::io)
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(MSP_INSTALL_INCLUDEDIR "${CMAKE_INSTALL_INCLUDEDIR}/ManifoldSplines")
set(MSP_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/ManifoldSplines")

# Headers that are not installed: implementation pieces that no public header includes (the
# installed-header test compiles every installed header alone, so a public header that includes
# one of these fails it). Besides this list, any header named *_internal.h or *_detail.h.
set(MSP_PRIVATE_HEADERS
  ricci/flow/flow_state.h
  ricci/flow/hessian.h
  ricci/flow/serial_blas.h
  ricci/mesh/cgal_convert.h
  ricci/mesh/parse_util.h
  ricci/mesh/soup_formats.h
  ricci/mesh/topology_util.h
  spline/fill/fill_system.h
  spline/fill/patch_domain.h
  spline/fit/correction.h
  spline/fit/normal_equations.h
  spline/io/byte_stream.h
  spline/tessellate/parallel_for.h)

# The include folder of a library target: the source folder when building, the installed one
# for a consumer of the package.
function(msp_library_includes target folder)
  target_include_directories(${target} PUBLIC
    "$<BUILD_INTERFACE:${folder}>" "$<INSTALL_INTERFACE:${MSP_INSTALL_INCLUDEDIR}>")
  target_compile_features(${target} PUBLIC cxx_std_17)
endfunction()

# Installs the public headers found under `folder` (an include root such as libricci/).
function(msp_install_headers folder)
  if(NOT MSP_INSTALL)
    return()
  endif()
  file(GLOB_RECURSE headers RELATIVE "${folder}" CONFIGURE_DEPENDS "${folder}/*.h")
  foreach(header ${headers})
    if(header MATCHES "_(internal|detail)\\.h$" OR header IN_LIST MSP_PRIVATE_HEADERS)
      continue()
    endif()
    get_filename_component(subfolder "${header}" DIRECTORY)
    install(FILES "${folder}/${header}" DESTINATION "${MSP_INSTALL_INCLUDEDIR}/${subfolder}")
  endforeach()
endfunction()

function(msp_install_package)
  install(TARGETS ricci spline msp_io EXPORT ManifoldSplinesTargets
    ARCHIVE DESTINATION "${CMAKE_INSTALL_LIBDIR}"
    LIBRARY DESTINATION "${CMAKE_INSTALL_LIBDIR}"
    RUNTIME DESTINATION "${CMAKE_INSTALL_BINDIR}")
  if(TARGET msp)
    install(TARGETS msp RUNTIME DESTINATION "${CMAKE_INSTALL_BINDIR}")
  endif()
  install(EXPORT ManifoldSplinesTargets NAMESPACE ManifoldSplines::
    FILE ManifoldSplinesTargets.cmake DESTINATION "${MSP_INSTALL_CMAKEDIR}")
  configure_package_config_file("${PROJECT_SOURCE_DIR}/cmake/ManifoldSplinesConfig.cmake.in"
    "${PROJECT_BINARY_DIR}/ManifoldSplinesConfig.cmake"
    INSTALL_DESTINATION "${MSP_INSTALL_CMAKEDIR}")
  # 0.x: a minor version may change the API, so only the same minor version is compatible.
  write_basic_package_version_file("${PROJECT_BINARY_DIR}/ManifoldSplinesConfigVersion.cmake"
    COMPATIBILITY SameMinorVersion)
  install(FILES
    "${PROJECT_BINARY_DIR}/ManifoldSplinesConfig.cmake"
    "${PROJECT_BINARY_DIR}/ManifoldSplinesConfigVersion.cmake"
    "${PROJECT_SOURCE_DIR}/cmake/ImportedLibraries.cmake"
    DESTINATION "${MSP_INSTALL_CMAKEDIR}")
endfunction()
