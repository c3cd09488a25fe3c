# MSP_PYTHON: ON builds python/ (fails without Python and nanobind), AUTO builds it when both are
# found, OFF never. Included after enable_testing(): the pytest suite joins ctest.
if(MSP_PYTHON STREQUAL "AUTO")
  find_package(Python 3.8 COMPONENTS Interpreter Development.Module)
  set(msp_nanobind_dir "")
  if(Python_FOUND)
    execute_process(COMMAND "${Python_EXECUTABLE}" -m nanobind --cmake_dir
      OUTPUT_VARIABLE msp_nanobind_dir OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  endif()
  if(msp_nanobind_dir)
    add_subdirectory(python)
  else()
    message(STATUS "Python extension off: Python 3.8+ with nanobind not found (MSP_PYTHON=ON)")
  endif()
elseif(MSP_PYTHON)
  add_subdirectory(python)
endif()
