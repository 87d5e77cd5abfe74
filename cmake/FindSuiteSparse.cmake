# FindSuiteSparse: Debian 12 ships SuiteSparse 5.12 without CMake package files, so this
# module locates the headers and libraries of the requested components.
#
#   find_package(SuiteSparse REQUIRED COMPONENTS CHOLMOD UMFPACK)
#
# Defines the imported targets SuiteSparse::<COMPONENT> (e.g. SuiteSparse::CHOLMOD) and
# SuiteSparse::SuiteSparseConfig, and SuiteSparse_FOUND.

find_path(SuiteSparse_INCLUDE_DIR NAMES SuiteSparse_config.h
          PATH_SUFFIXES suitesparse)
find_library(SuiteSparse_CONFIG_LIBRARY NAMES suitesparseconfig)

set(_ss_required SuiteSparse_INCLUDE_DIR SuiteSparse_CONFIG_LIBRARY)
foreach(_comp IN LISTS SuiteSparse_FIND_COMPONENTS)
  string(TOLOWER ${_comp} _lower)
  find_library(SuiteSparse_${_comp}_LIBRARY NAMES ${_lower})
  find_path(SuiteSparse_${_comp}_INCLUDE_DIR NAMES ${_lower}.h PATH_SUFFIXES suitesparse)
  if(SuiteSparse_${_comp}_LIBRARY AND SuiteSparse_${_comp}_INCLUDE_DIR)
    set(SuiteSparse_${_comp}_FOUND TRUE)
  endif()
endforeach()

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(SuiteSparse REQUIRED_VARS ${_ss_required}
                                  HANDLE_COMPONENTS)

if(SuiteSparse_FOUND AND NOT TARGET SuiteSparse::SuiteSparseConfig)
  add_library(SuiteSparse::SuiteSparseConfig UNKNOWN IMPORTED)
  set_target_properties(SuiteSparse::SuiteSparseConfig PROPERTIES
    IMPORTED_LOCATION "${SuiteSparse_CONFIG_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${SuiteSparse_INCLUDE_DIR}")
  foreach(_comp IN LISTS SuiteSparse_FIND_COMPONENTS)
    if(SuiteSparse_${_comp}_FOUND)
      add_library(SuiteSparse::${_comp} UNKNOWN IMPORTED)
      set_target_properties(SuiteSparse::${_comp} PROPERTIES
        IMPORTED_LOCATION "${SuiteSparse_${_comp}_LIBRARY}"
        INTERFACE_INCLUDE_DIRECTORIES "${SuiteSparse_${_comp}_INCLUDE_DIR}"
        INTERFACE_LINK_LIBRARIES SuiteSparse::SuiteSparseConfig)
    endif()
  endforeach()
endif()
mark_as_advanced(SuiteSparse_INCLUDE_DIR SuiteSparse_CONFIG_LIBRARY)
