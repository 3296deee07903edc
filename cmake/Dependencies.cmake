# Every third-party dependency is found here, once, and exposed as an imported target. Only what
# some target links is found: CGAL comes back with its first user (cluster/install-deps.sh already
# installs it).
# On a cluster, point CMake at module-provided installs with <Pkg>_ROOT or PKG_CONFIG_PATH
# (see docs/cluster.md).

find_package(MPI 3.1 REQUIRED COMPONENTS C CXX)

# Two HDF5 builds of the same release: the parallel one (MPI-IO) for clatter-bank, the serial one
# for clatter-synth, which must run without an MPI runtime. No binary links both (io/CMakeLists.txt).
set(HDF5_PREFER_PARALLEL TRUE)
find_package(HDF5 REQUIRED COMPONENTS C)
if(NOT HDF5_IS_PARALLEL)
  message(FATAL_ERROR
    "Clatter needs a parallel (MPI-IO) HDF5, but the HDF5 found (${HDF5_VERSION}, "
    "includes ${HDF5_C_INCLUDE_DIRS}) is serial. Debian: apt-get install libhdf5-openmpi-dev. "
    "Cluster: load the parallel HDF5 module and configure with -DHDF5_ROOT=<its prefix>.")
endif()
add_library(clatter_hdf5_mpi INTERFACE)
target_include_directories(clatter_hdf5_mpi SYSTEM INTERFACE ${HDF5_C_INCLUDE_DIRS})
target_compile_definitions(clatter_hdf5_mpi INTERFACE ${HDF5_C_DEFINITIONS})
target_link_libraries(clatter_hdf5_mpi INTERFACE ${HDF5_C_LIBRARIES} MPI::MPI_C)
# libhdf5 itself, for tests/cli/install_checks.sh (which checks that clatter-bank loads it).
set(CLATTER_HDF5_MPI_LIBRARY ${HDF5_C_LIBRARY_hdf5})
if(NOT CLATTER_HDF5_MPI_LIBRARY)
  set(CLATTER_HDF5_MPI_LIBRARY ${HDF5_C_LIBRARIES})
  list(FILTER CLATTER_HDF5_MPI_LIBRARY INCLUDE REGEX "hdf5[^/]*$")
  list(POP_FRONT CLATTER_HDF5_MPI_LIBRARY CLATTER_HDF5_MPI_LIBRARY)
endif()

find_package(PkgConfig REQUIRED)
include(SerialHDF5)

find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(GSL 2.7 REQUIRED)
find_package(toml11 3.7 REQUIRED)
find_package(CLI11 2.1 REQUIRED)
find_package(fmt 9 REQUIRED)
find_package(spdlog 1.10 REQUIRED)
find_package(nlohmann_json 3.11 REQUIRED)
find_package(nanoflann 1.4 REQUIRED)  # synth/modal_voices.cpp: the nearest modal proxy (header only)
find_package(Threads REQUIRED)  # core/file_lock.cpp: the heartbeat thread of a lock
pkg_check_modules(sndfile REQUIRED IMPORTED_TARGET sndfile>=1.2)
# The modal bank's eigen-solves (petsc/). Debian: libpetsc-real3.18-dev, libslepc-real3.18-dev (real
# double, 32-bit PetscInt, MUMPS). PETSc.pc names no MPI include folder: clatter_petsc links
# MPI::MPI_CXX itself.
pkg_check_modules(PETSC REQUIRED IMPORTED_TARGET PETSc>=3.18)
pkg_check_modules(SLEPC REQUIRED IMPORTED_TARGET SLEPc>=3.18)
# TetGen 1.5 (Debian: libtet1.5-dev) for kernels/fem/ellipsoid_mesh.cpp: no CMake config or .pc,
# so header and library are found by name; TETLIBRARY makes TetGen throw instead of exit().
# SYSTEM: its header is not warning-free under the project's flags.
find_path(TETGEN_INCLUDE_DIR tetgen.h REQUIRED)
find_library(TETGEN_LIBRARY NAMES tet tetgen REQUIRED)
add_library(clatter_tetgen INTERFACE)
target_include_directories(clatter_tetgen SYSTEM INTERFACE ${TETGEN_INCLUDE_DIR})
target_compile_definitions(clatter_tetgen INTERFACE TETLIBRARY)
target_link_libraries(clatter_tetgen INTERFACE ${TETGEN_LIBRARY})
# clatter-sim (sim/) only: Bullet's double-precision build (Debian libbullet-dev ships both; its
# .pc file adds -DBT_USE_DOUBLE_PRECISION, which must match the library) and voro++ (Debian
# voro++-dev: no CMake config or .pc, found by name; SYSTEM: its headers are not warning-free).
pkg_check_modules(BULLET REQUIRED IMPORTED_TARGET bullet-float64>=2.89)
find_path(VORO_INCLUDE_DIR voro++/voro++.hh REQUIRED)
find_library(VORO_LIBRARY NAMES voro++ REQUIRED)
add_library(clatter_voro INTERFACE)
target_include_directories(clatter_voro SYSTEM INTERFACE ${VORO_INCLUDE_DIR})
target_link_libraries(clatter_voro INTERFACE ${VORO_LIBRARY})
find_package(GTest REQUIRED)
find_package(benchmark REQUIRED)

# Analysis scripts and file-format tests need a python3 that imports h5py and numpy: the first one
# on PATH that does, else Debian's /usr/bin/python3 (python3-h5py installs there).
if(NOT CLATTER_PYTHON)
  find_program(_path_python NAMES python3 NO_CACHE)
  foreach(_candidate ${_path_python} /usr/bin/python3)
    execute_process(COMMAND ${_candidate} -c "import h5py, numpy" RESULT_VARIABLE _py_rc OUTPUT_QUIET ERROR_QUIET)
    if(_py_rc EQUAL 0)
      set(CLATTER_PYTHON ${_candidate} CACHE FILEPATH "python3 with h5py and numpy")
      break()
    endif()
  endforeach()
endif()
if(NOT CLATTER_PYTHON)
  message(FATAL_ERROR "No python3 that imports h5py and numpy (Debian: python3-h5py python3-numpy); "
                      "configure with -DCLATTER_PYTHON=<a python3 that can>")
endif()
