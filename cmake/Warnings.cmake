# Warnings and sanitizers applied to every target of the project (not to dependencies).
function(msp_target_defaults target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic)
  # GCC 12 reports OpenMesh's uninitialised-by-design VectorT default constructor (a false
  # positive inside OpenMesh's property containers) and Eigen temporaries; it hides nothing of ours.
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    target_compile_options(${target} PRIVATE -Wno-maybe-uninitialized)
  endif()
  if(MSP_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

if(MSP_SANITIZE)
  # float-cast-overflow is not part of GCC's "undefined": a double past the range of int
  # converted to int (a grid cell of a far point) is undefined behaviour all the same.
  add_compile_options(-fsanitize=address,undefined,float-cast-overflow -fno-omit-frame-pointer
                      -fno-sanitize-recover=undefined,float-cast-overflow)
  # Eigen takes glibc's malloc as aligned only without __SANITIZE_ADDRESS__: the uninstrumented
  # CGAL translation units (libricci/CMakeLists.txt) would allocate with malloc what instrumented
  # ones free with Eigen's handmade aligned_free. One allocator for every translation unit.
  add_compile_definitions(EIGEN_MALLOC_ALREADY_ALIGNED=0)
  add_link_options(-fsanitize=address,undefined,float-cast-overflow)
endif()
if(MSP_SANITIZE_THREAD)
  # Data races between our threads (parallel_for, the stages run beside each other). Libraries
  # built without it (CHOLMOD, OpenBLAS, libgomp) are invisible to it: races inside their own
  # threads are not reported.
  add_compile_options(-fsanitize=thread -fno-omit-frame-pointer -g)
  add_link_options(-fsanitize=thread)
endif()
