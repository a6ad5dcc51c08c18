# FRICTION-EQ: what every CMake route of the package shares (the wrapper
# build in the repository root, the plugin build in plugin/).
#
#   feq_lammps_version(<LAMMPS src dir> <out number> <out text>)
#       "29 Sep 2021" -> 20210929 (FEQ_LAMMPS_VERSION, see eq_lammps_compat.h)
#   feq_add_core()
#       feq_core: the LAMMPS-free physics kernels the styles use
#       (distributions, random draws, master equation, kernels, substrate),
#       no external dependency; position-independent (liblammps, plugins)
#   FEQ_STYLE_SOURCES
#       the LAMMPS styles of the package (src/FRICTION-EQ/*.cpp)
#   FEQ_COMPILE_OPTIONS
#       compile options for the package's sources (see below)
#
# The surface Green tensor solver (lib/eq_green.*, FFTW3 + Eigen3) is not
# part of feq_core: only the eq-green tool and its tests link it.

set(FEQ_PKG_DIR "${CMAKE_CURRENT_LIST_DIR}")
file(GLOB FEQ_STYLE_SOURCES CONFIGURE_DEPENDS "${FEQ_PKG_DIR}/*.cpp")
set(FEQ_GREEN_SOURCES "${FEQ_PKG_DIR}/lib/eq_green.cpp")

function(feq_lammps_version lammps_src out_number out_text)
  file(STRINGS "${lammps_src}/version.h" _line REGEX "^#define LAMMPS_VERSION ")
  if(NOT _line MATCHES "\"([0-9]+) ([A-Z][a-z][a-z]) ([0-9][0-9][0-9][0-9])\"")
    message(FATAL_ERROR "FRICTION-EQ: cannot read the LAMMPS version from "
      "${lammps_src}/version.h (got '${_line}')")
  endif()
  set(_day ${CMAKE_MATCH_1})
  set(_year ${CMAKE_MATCH_3})
  set(_months Jan Feb Mar Apr May Jun Jul Aug Sep Oct Nov Dec)
  list(FIND _months ${CMAKE_MATCH_2} _m)
  if(_m LESS 0)
    message(FATAL_ERROR "FRICTION-EQ: unknown month '${CMAKE_MATCH_2}' in ${lammps_src}/version.h")
  endif()
  math(EXPR _number "${_year} * 10000 + (${_m} + 1) * 100 + ${_day}")
  set(${out_number} ${_number} PARENT_SCOPE)
  set(${out_text} "${_day} ${CMAKE_MATCH_2} ${_year}" PARENT_SCOPE)
endfunction()

# a LAMMPS tree the package supports: 29 Sep 2021 or later, with the
# package folders the build needs
set(FEQ_LAMMPS_OLDEST 20210929)
function(feq_check_lammps lammps_dir number text packages)
  if(number LESS FEQ_LAMMPS_OLDEST)
    message(FATAL_ERROR "FRICTION-EQ: the LAMMPS tree ${lammps_dir} is version '${text}' "
      "(${number}); supported: 29 Sep 2021 (${FEQ_LAMMPS_OLDEST}) and later (tested: 29 Sep 2021, "
      "4 Feb 2025, 4 Jul 2026)")
  endif()
  set(_missing "")
  foreach(_pkg ${packages})
    if(NOT IS_DIRECTORY "${lammps_dir}/src/${_pkg}")
      list(APPEND _missing ${_pkg})
    endif()
  endforeach()
  if(_missing)
    string(REPLACE ";" ", " _missing "${_missing}")
    string(REPLACE ";" ", " _all "${packages}")
    message(FATAL_ERROR "FRICTION-EQ: the LAMMPS tree ${lammps_dir} ('${text}') has no package "
      "folder for ${_missing} in src/; the build needs ${_all} (bonds, rigid bodies, fix smd and "
      "fix brownian of the examples and tests): use a full LAMMPS source tree")
  endif()
endfunction()

# FEQ_COMPILE_OPTIONS: compile options for the package's sources.
# -fno-semantic-interposition: position-independent code calls the
# functions of its own library through the PLT, so that another library
# could interpose them, and never inlines them; the package's calls among
# its own functions (a contact's step, its bounds and draws; a style's
# helpers) are direct and may be inlined.  -ffp-contract=off: no fused
# multiply-add where the source has a product and a sum (GCC fuses them
# in its GNU modes on targets with FMA, e.g. aarch64, more so where code
# is inlined): the same numbers on every target and build
include(CheckCXXCompilerFlag)
check_cxx_compiler_flag(-fno-semantic-interposition FEQ_HAS_NO_INTERPOSITION)
check_cxx_compiler_flag(-ffp-contract=off FEQ_HAS_FP_CONTRACT_OFF)
set(FEQ_COMPILE_OPTIONS "")
if(FEQ_HAS_NO_INTERPOSITION)
  list(APPEND FEQ_COMPILE_OPTIONS -fno-semantic-interposition)
endif()
if(FEQ_HAS_FP_CONTRACT_OFF)
  list(APPEND FEQ_COMPILE_OPTIONS -ffp-contract=off)
endif()

function(feq_add_core)
  file(GLOB _lib CONFIGURE_DEPENDS "${FEQ_PKG_DIR}/lib/*.cpp")
  list(REMOVE_ITEM _lib ${FEQ_GREEN_SOURCES})
  add_library(feq_core STATIC ${_lib})
  target_include_directories(feq_core PUBLIC "${FEQ_PKG_DIR}/lib")
  target_compile_features(feq_core PUBLIC cxx_std_11)
  set_target_properties(feq_core PROPERTIES POSITION_INDEPENDENT_CODE ON)
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(feq_core PRIVATE -Wall -Wextra)
  endif()
  target_compile_options(feq_core PRIVATE ${FEQ_COMPILE_OPTIONS})
endfunction()
