# FindKLU: KLU (sparse LU for sequences of matrices with one pattern) from
# SuiteSparse, as the imported target KLU::KLU. Same situation as
# FindCHOLMOD.cmake: SuiteSparse >= 7 ships a config (SuiteSparse::KLU),
# Debian's 5.x only the header and the libraries.
#   KLU_FOUND, KLU_INCLUDE_DIR, KLU_LIBRARY

include(FindPackageHandleStandardArgs)

find_package(KLU CONFIG QUIET NO_MODULE)
if(TARGET SuiteSparse::KLU)
  if(NOT TARGET KLU::KLU)
    add_library(KLU::KLU INTERFACE IMPORTED)
    set_target_properties(KLU::KLU PROPERTIES INTERFACE_LINK_LIBRARIES SuiteSparse::KLU)
  endif()
  set(KLU_FOUND TRUE)
  return()
endif()

find_path(KLU_INCLUDE_DIR klu.h PATH_SUFFIXES suitesparse)
find_library(KLU_LIBRARY klu)
find_library(KLU_BTF_LIBRARY btf)
find_library(KLU_AMD_LIBRARY amd)
find_library(KLU_COLAMD_LIBRARY colamd)
find_library(KLU_SUITESPARSECONFIG_LIBRARY suitesparseconfig)

find_package_handle_standard_args(KLU
  REQUIRED_VARS KLU_LIBRARY KLU_INCLUDE_DIR KLU_BTF_LIBRARY KLU_AMD_LIBRARY KLU_COLAMD_LIBRARY)

if(KLU_FOUND AND NOT TARGET KLU::KLU)
  add_library(KLU::KLU UNKNOWN IMPORTED)
  set_target_properties(KLU::KLU PROPERTIES
    IMPORTED_LOCATION "${KLU_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${KLU_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${KLU_BTF_LIBRARY};${KLU_AMD_LIBRARY};${KLU_COLAMD_LIBRARY};${KLU_SUITESPARSECONFIG_LIBRARY}")
endif()
mark_as_advanced(KLU_INCLUDE_DIR KLU_LIBRARY KLU_BTF_LIBRARY KLU_AMD_LIBRARY KLU_COLAMD_LIBRARY
                 KLU_SUITESPARSECONFIG_LIBRARY)
