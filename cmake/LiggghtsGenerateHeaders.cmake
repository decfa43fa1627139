# Runs LIGGGHTS' own style-header generator in the patched source tree:
#   cmake -DSRC_DIR=<patched src> [-DPATCH_NAMES=a,b] [-DSTAMP=<file>] -P LiggghtsGenerateHeaders.cmake
# `sh Make.sh style` writes style_<kind>.h (rewritten only when their content changes) and
# `sh Make.sh models` writes style_contact_model.h. Two adjustments keep rebuilds minimal:
#  * version_liggghts.h: Make.sh puts the date into it on every run; we replace it by a
#    deterministic line and keep the old file (and its mtime) when that line is unchanged.
#  * style_contact_model.whitelist: Make.sh reuses it when present, so it is deleted when the
#    set of contact-model headers (*_model_*.h) changes, to pick up new models.
cmake_minimum_required(VERSION 3.18)
if(NOT SRC_DIR OR NOT EXISTS "${SRC_DIR}/Make.sh")
  message(FATAL_ERROR "LiggghtsGenerateHeaders: SRC_DIR (${SRC_DIR}) has no Make.sh")
endif()

# --- contact models changed? ---------------------------------------------------------------
file(GLOB _model_headers RELATIVE "${SRC_DIR}" "${SRC_DIR}/*_model_*.h")
list(SORT _model_headers)
set(_models_key "")
foreach(_h IN LISTS _model_headers)
  file(STRINGS "${SRC_DIR}/${_h}" _lines REGEX "^(SURFACE|NORMAL|TANGENTIAL|COHESION|ROLLING)_MODEL\\(")
  string(APPEND _models_key "${_h}: ${_lines}\n")
endforeach()
set(_models_keyfile "${SRC_DIR}/../contact_models.key")
set(_old_models_key "")
if(EXISTS "${_models_keyfile}")
  file(READ "${_models_keyfile}" _old_models_key)
endif()
if(NOT _old_models_key STREQUAL _models_key)
  file(REMOVE "${SRC_DIR}/style_contact_model.whitelist")
endif()

# --- Make.sh -------------------------------------------------------------------------------
set(_version_h "${SRC_DIR}/version_liggghts.h")
if(EXISTS "${_version_h}")
  file(RENAME "${_version_h}" "${_version_h}.keep")
endif()
foreach(_what style models)
  execute_process(COMMAND sh Make.sh ${_what} WORKING_DIRECTORY "${SRC_DIR}"
                  RESULT_VARIABLE _rv OUTPUT_VARIABLE _out ERROR_VARIABLE _out)
  if(NOT _rv EQUAL 0)
    message(FATAL_ERROR "LiggghtsGenerateHeaders: `sh Make.sh ${_what}` failed in ${SRC_DIR}:\n${_out}")
  endif()
endforeach()
file(WRITE "${_models_keyfile}" "${_models_key}")

# --- deterministic version_liggghts.h ------------------------------------------------------
file(STRINGS "${SRC_DIR}/version_liggghts_branch.txt" _branch LIMIT_COUNT 1)
file(STRINGS "${SRC_DIR}/version_liggghts.txt" _version LIMIT_COUNT 1)
string(REPLACE "," " " _patches "${PATCH_NAMES}")
string(REPLACE "\"" "" _patches "${_patches}")
set(_line "#define LIGGGHTS_VERSION \"${_branch} ${_version}, spacetree-dem build, patches: ${_patches}\"\n")
set(_kept FALSE)
if(EXISTS "${_version_h}.keep")
  file(READ "${_version_h}.keep" _old_line)
  if(_old_line STREQUAL _line)
    file(RENAME "${_version_h}.keep" "${_version_h}")
    set(_kept TRUE)
  else()
    file(REMOVE "${_version_h}.keep")
  endif()
endif()
if(NOT _kept)
  file(WRITE "${_version_h}" "${_line}")
endif()

if(STAMP)
  file(TOUCH "${STAMP}")
endif()
