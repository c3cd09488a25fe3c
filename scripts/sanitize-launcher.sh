#!/bin/sh
# A ccache launcher that instruments with ASan + UBSan only the sources matching
# $MSP_SANITIZE_SOURCES (an extended regex; default: the threaded and SSE2 code of the DMS
# kernel, fit_surface, the singularity choice, the one-cone pipeline, the atlas and its
# distortion, the linear solver). Every other source compiles exactly as a Release build does,
# so it comes from ccache: a sanitized run of the new code in minutes where the full
# -DMSP_SANITIZE=ON build takes hours on a busy machine. Instrumented commands hash apart.
# Eigen: every translation unit takes malloc as aligned (the uninstrumented ones detect it), so
# the instrumented ones say so too (EIGEN_MALLOC_ALREADY_ALIGNED=1): one allocator for all.
#
#   cmake -S . -B build-san -G Ninja -DCMAKE_BUILD_TYPE=Release -DMSP_WERROR=ON -DMSP_PYTHON=OFF \
#     -DCCACHE_PROGRAM=$PWD/scripts/sanitize-launcher.sh \
#     -DCMAKE_EXE_LINKER_FLAGS=-fsanitize=address,undefined \
#     -DCMAKE_SHARED_LINKER_FLAGS=-fsanitize=address,undefined
#
# CGAL translation units (*_cgal.cpp) stay uninstrumented, as with MSP_SANITIZE.
default='libspline/spline/basis/|libspline/spline/surface/fit_surface\.cpp|libricci/ricci/(singularity|pipeline|quality|atlas)/|libricci/ricci/flow/(linear_solver|serial_blas)\.cpp'
pattern=${MSP_SANITIZE_SOURCES:-$default}
ccache=$(command -v ccache)
src=""
prev=""
for a in "$@"; do
  if [ "$prev" = "-c" ]; then src="$a"; fi
  prev="$a"
done
if [ -n "$src" ] && echo "$src" | grep -Eq "$pattern" && ! echo "$src" | grep -q '_cgal\.cpp$'; then
  exec "$ccache" "$@" -fsanitize=address,undefined,float-cast-overflow -fno-omit-frame-pointer \
    -fno-sanitize-recover=undefined,float-cast-overflow -DEIGEN_MALLOC_ALREADY_ALIGNED=1 -g1
fi
exec "$ccache" "$@"
