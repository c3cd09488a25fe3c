# Steps of the install tests (tests/install/CMakeLists.txt), run with cmake -P:
#   install   a fresh `cmake --install MSP_BUILD_DIR --prefix MSP_WORK_DIR/prefix`
#   examples  configure and build examples/ against the prefix, run both programs on
#             models/genus2.off and check their outputs
#   headers   compile every installed header alone (tests/install/headers)
#   subdirectory  configure tests/install/subdirectory, which add_subdirectory()s the project
cmake_minimum_required(VERSION 3.22)
set(prefix "${MSP_WORK_DIR}/prefix")

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    string(REPLACE ";" " " command "${ARGN}")
    message(FATAL_ERROR "failed (${status}): ${command}\n${out}\n${err}")
  endif()
  set(run_output "${out}" PARENT_SCOPE)
endfunction()

# Configures and builds the outside project in `source` against the installed prefix only.
function(build_outside source binary)
  file(REMOVE_RECURSE "${binary}")
  set(launcher "")
  find_program(ccache ccache)
  if(ccache)
    set(launcher "-DCMAKE_CXX_COMPILER_LAUNCHER=${ccache}")
    # Paths relative to the source tree in the cache key (as the project's own build does): hits
    # across clones whose build tree is inside the source tree.
    set(ENV{CCACHE_BASEDIR} "${MSP_SOURCE_DIR}")
    set(ENV{CCACHE_NOHASHDIR} 1)
  endif()
  run(${CMAKE_COMMAND} -S "${source}" -B "${binary}" -G "${MSP_GENERATOR}"
      -DCMAKE_BUILD_TYPE=Release "-DCMAKE_CXX_COMPILER=${MSP_CXX_COMPILER}" ${launcher}
      "-DCMAKE_PREFIX_PATH=${prefix}" ${ARGN})
  run(${CMAKE_COMMAND} --build "${binary}")
endfunction()

# Fails unless `file` exists and starts with the bytes `magic` (hex).
function(expect_file_starts_with file magic)
  if(NOT EXISTS "${file}")
    message(FATAL_ERROR "${file} was not written")
  endif()
  string(LENGTH "${magic}" hex_length)
  math(EXPR bytes "${hex_length} / 2")
  file(READ "${file}" head LIMIT ${bytes} HEX)
  if(NOT head STREQUAL magic)
    message(FATAL_ERROR "${file} starts with ${head}, not ${magic}")
  endif()
endfunction()

if(MSP_STEP STREQUAL "install")
  file(REMOVE_RECURSE "${MSP_WORK_DIR}")
  run(${CMAKE_COMMAND} --install "${MSP_BUILD_DIR}" --prefix "${prefix}")
  foreach(file lib/cmake/ManifoldSplines/ManifoldSplinesConfig.cmake
               lib/cmake/ManifoldSplines/ManifoldSplinesConfigVersion.cmake
               include/ManifoldSplines/spline/fit/fit.h include/ManifoldSplines/msp/io/gltf_writer.h)
    if(NOT EXISTS "${prefix}/${file}")
      message(FATAL_ERROR "cmake --install did not write ${file}")
    endif()
  endforeach()
  # Implementation headers stay out of the package.
  foreach(file ricci/flow/flow_internal.h ricci/mesh/cgal_convert.h spline/fill/fill_system.h)
    if(EXISTS "${prefix}/include/ManifoldSplines/${file}")
      message(FATAL_ERROR "the private header ${file} was installed")
    endif()
  endforeach()

elseif(MSP_STEP STREQUAL "examples")
  set(binary "${MSP_WORK_DIR}/examples")
  build_outside("${MSP_SOURCE_DIR}/examples" "${binary}")
  set(model "${MSP_SOURCE_DIR}/models/genus2.off")
  run("${binary}/fit_scan" "${model}" "${binary}/genus2.msp" "${binary}/genus2.ply" 400)
  message(STATUS "${run_output}")
  run("${binary}/edit_spline" "${binary}/genus2.msp" "${binary}/genus2_swollen.glb")
  message(STATUS "${run_output}")
  # PLY header "ply\nformat binary"; GLB header: magic "glTF", version 2.
  expect_file_starts_with("${binary}/genus2.ply" "706c790a666f726d61742062696e617279")
  expect_file_starts_with("${binary}/genus2_swollen.glb" "676c544602000000")
  file(SIZE "${binary}/genus2_swollen.glb" glb_size)
  file(READ "${binary}/genus2_swollen.glb" length_hex OFFSET 8 LIMIT 4 HEX)
  string(REGEX REPLACE "(..)(..)(..)(..)" "\\4\\3\\2\\1" length_hex "${length_hex}")
  math(EXPR glb_length "0x${length_hex}")
  if(NOT glb_length EQUAL glb_size)
    message(FATAL_ERROR "the .glb says it has ${glb_length} bytes, the file has ${glb_size}")
  endif()
  # The fitted surface read back by the installed msp: a closed genus-2 2-manifold (the cone's
  # hole capped by its patch, as msp fit writes it); and the installed msp reads the spline.
  run("${prefix}/bin/msp" info --json "${binary}/genus2.ply")
  string(JSON genus GET "${run_output}" genus)
  string(JSON loops GET "${run_output}" boundary_loops)
  string(JSON manifold GET "${run_output}" manifold)
  if(NOT genus EQUAL 2 OR NOT loops EQUAL 0 OR NOT manifold)
    message(FATAL_ERROR "genus2.ply: genus ${genus}, ${loops} boundary loops, manifold ${manifold}")
  endif()
  run("${prefix}/bin/msp" tessellate "${binary}/genus2.msp" -o "${binary}/again.ply" --json)

elseif(MSP_STEP STREQUAL "subdirectory")
  set(binary "${MSP_WORK_DIR}-subdirectory")  # not in the fixture's folder: runs alongside
  file(REMOVE_RECURSE "${binary}")
  run(${CMAKE_COMMAND} -S "${MSP_SOURCE_DIR}/tests/install/subdirectory" -B "${binary}"
      -G "${MSP_GENERATOR}" "-DCMAKE_CXX_COMPILER=${MSP_CXX_COMPILER}"
      "-DMSP_SOURCE_DIR=${MSP_SOURCE_DIR}")

elseif(MSP_STEP STREQUAL "headers")
  build_outside("${MSP_SOURCE_DIR}/tests/install/headers" "${MSP_WORK_DIR}/headers")

else()
  message(FATAL_ERROR "unknown MSP_STEP '${MSP_STEP}'")
endif()
