# FindCHOLMOD: CHOLMOD from SuiteSparse, as the imported target CHOLMOD::CHOLMOD.
# Debian's SuiteSparse 5.x ships no CMake config and no .pc file, so we look
# for the header and the libraries ourselves; SuiteSparse >= 7 ships a config
# (SuiteSparse::CHOLMOD), which we use when present.
#   CHOLMOD_FOUND, CHOLMOD_VERSION, CHOLMOD_INCLUDE_DIR, CHOLMOD_LIBRARY

include(FindPackageHandleStandardArgs)

find_package(CHOLMOD CONFIG QUIET NO_MODULE)
if(TARGET SuiteSparse::CHOLMOD)
  if(NOT TARGET CHOLMOD::CHOLMOD)
    add_library(CHOLMOD::CHOLMOD INTERFACE IMPORTED)
    set_target_properties(CHOLMOD::CHOLMOD PROPERTIES INTERFACE_LINK_LIBRARIES SuiteSparse::CHOLMOD)
  endif()
  set(CHOLMOD_FOUND TRUE)
  return()
endif()

find_path(CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse)
find_library(CHOLMOD_LIBRARY cholmod)
find_library(SUITESPARSECONFIG_LIBRARY suitesparseconfig)
foreach(_dep amd colamd camd ccolamd)
  string(TOUPPER ${_dep} _DEP)
  find_library(${_DEP}_LIBRARY ${_dep})
  if(${_DEP}_LIBRARY)
    list(APPEND _cholmod_deps ${${_DEP}_LIBRARY})
  endif()
endforeach()

if(CHOLMOD_INCLUDE_DIR AND EXISTS "${CHOLMOD_INCLUDE_DIR}/cholmod_core.h")
  file(STRINGS "${CHOLMOD_INCLUDE_DIR}/cholmod_core.h" _ver REGEX "#define CHOLMOD_(MAIN|SUB|SUBSUB)_VERSION")
  string(REGEX REPLACE ".*CHOLMOD_MAIN_VERSION +([0-9]+).*" "\\1" _major "${_ver}")
  string(REGEX REPLACE ".*CHOLMOD_SUB_VERSION +([0-9]+).*" "\\1" _minor "${_ver}")
  string(REGEX REPLACE ".*CHOLMOD_SUBSUB_VERSION +([0-9]+).*" "\\1" _patch "${_ver}")
  set(CHOLMOD_VERSION "${_major}.${_minor}.${_patch}")
endif()

find_package_handle_standard_args(CHOLMOD
  REQUIRED_VARS CHOLMOD_LIBRARY CHOLMOD_INCLUDE_DIR SUITESPARSECONFIG_LIBRARY
  VERSION_VAR CHOLMOD_VERSION)

if(CHOLMOD_FOUND AND NOT TARGET CHOLMOD::CHOLMOD)
  # BLAS/LAPACK need no explicit link: libcholmod.so already depends on them.
  add_library(CHOLMOD::CHOLMOD UNKNOWN IMPORTED)
  set_target_properties(CHOLMOD::CHOLMOD PROPERTIES
    IMPORTED_LOCATION "${CHOLMOD_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${CHOLMOD_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${_cholmod_deps};${SUITESPARSECONFIG_LIBRARY}")
endif()
mark_as_advanced(CHOLMOD_INCLUDE_DIR CHOLMOD_LIBRARY SUITESPARSECONFIG_LIBRARY)
