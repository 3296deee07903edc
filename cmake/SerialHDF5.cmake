# The serial HDF5, as target clatter_hdf5_serial. A second find_package(HDF5) would collide with
# the parallel one's cached variables, so: pkg-config's hints (Debian's libhdf5-dev ships
# hdf5-serial.pc), then find_path/find_library under CLATTER_HDF5_SERIAL_ROOT or those hints, and
# a check of H5pubconf.h that what was found really is serial.

set(CLATTER_HDF5_SERIAL_ROOT "" CACHE PATH "prefix of a serial HDF5 (include/hdf5.h, lib/libhdf5)")
pkg_check_modules(_hdf5_serial_pc QUIET hdf5-serial)
find_path(CLATTER_HDF5_SERIAL_INCLUDE_DIR hdf5.h
  HINTS ${CLATTER_HDF5_SERIAL_ROOT}/include ${_hdf5_serial_pc_INCLUDE_DIRS}
  PATHS /usr/include/hdf5/serial
  NO_DEFAULT_PATH)
find_library(CLATTER_HDF5_SERIAL_LIBRARY NAMES hdf5_serial hdf5
  HINTS ${CLATTER_HDF5_SERIAL_ROOT}/lib ${_hdf5_serial_pc_LIBRARY_DIRS}
  PATHS /usr/lib/${CMAKE_LIBRARY_ARCHITECTURE}/hdf5/serial
  NO_DEFAULT_PATH)

set(_why "")
if(NOT CLATTER_HDF5_SERIAL_INCLUDE_DIR OR NOT CLATTER_HDF5_SERIAL_LIBRARY)
  set(_why "not found")
elseif(NOT EXISTS ${CLATTER_HDF5_SERIAL_INCLUDE_DIR}/H5pubconf.h)
  set(_why "no H5pubconf.h beside ${CLATTER_HDF5_SERIAL_INCLUDE_DIR}/hdf5.h")
else()
  file(STRINGS ${CLATTER_HDF5_SERIAL_INCLUDE_DIR}/H5pubconf.h _parallel REGEX "^#define H5_HAVE_PARALLEL ")
  if(_parallel)
    set(_why "${CLATTER_HDF5_SERIAL_INCLUDE_DIR} is a parallel HDF5")
  endif()
endif()
if(_why)
  message(FATAL_ERROR
    "Serial HDF5 (for clatter-synth, which runs without MPI): ${_why}. Debian: apt-get install libhdf5-dev "
    "(installs beside libhdf5-openmpi-dev). Elsewhere: -DCLATTER_HDF5_SERIAL_ROOT=<prefix of a serial HDF5> "
    "or -DCLATTER_HDF5_SERIAL_INCLUDE_DIR=... -DCLATTER_HDF5_SERIAL_LIBRARY=...")
endif()
message(STATUS "Serial HDF5: ${CLATTER_HDF5_SERIAL_LIBRARY} (includes ${CLATTER_HDF5_SERIAL_INCLUDE_DIR})")

add_library(clatter_hdf5_serial INTERFACE)
target_include_directories(clatter_hdf5_serial SYSTEM INTERFACE ${CLATTER_HDF5_SERIAL_INCLUDE_DIR})
target_link_libraries(clatter_hdf5_serial INTERFACE ${CLATTER_HDF5_SERIAL_LIBRARY})
