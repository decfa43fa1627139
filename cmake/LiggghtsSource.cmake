# Prepares the patched LIGGGHTS source tree inside the build tree (configure time).
#
#   pristine src/ (tarball or checkout, never modified)
#     -> <WORK_DIR>/stage/src, patched with `patch -p1` in the order of liggghts_patch/series
#     -> synced by content into <WORK_DIR>/src (only files whose content changed are rewritten,
#        so a changed patch recompiles only what it touches)
#     -> symlinks to our adapter files (src/liggghts/*) added next to them
#     -> style_*.h generated with Make.sh (cmake/LiggghtsGenerateHeaders.cmake)
#
# The work is skipped when <WORK_DIR>/source.stamp matches the hashes of the source, the series
# and every listed patch. The series and the patches are CMAKE_CONFIGURE_DEPENDS, so editing them
# re-runs CMake on the next build, which re-applies the series.
include_guard(GLOBAL)

set(LIGGGHTS_SOURCE_DIR "" CACHE PATH
    "LIGGGHTS-PUBLIC-3.8.0 checkout whose src/ is used (empty: extract LIGGGHTS_TARBALL)")
set(LIGGGHTS_TARBALL "${PROJECT_SOURCE_DIR}/.deps/liggghts_3.8.0+repack1.orig.tar.xz" CACHE FILEPATH
    "Pristine LIGGGHTS 3.8.0 source tarball (downloaded by scripts/setup.sh)")
find_program(PATCH_EXECUTABLE patch)
find_program(SH_EXECUTABLE sh)

# Bump when the preparation below changes in a way that needs a fresh tree.
set(_LG_RECIPE_VERSION 1)
# Files of a checkout's src/ that are build products, not sources.
set(_LG_EXCLUDE_REGEX "(^|/)Obj_[^/]*/|^style_[^/]*\\.(h|tmp)$|^style_contact_model\\.whitelist$|^version_liggghts\\.h$|\\.(o|d|a|so)$")

function(spacetree_prepare_liggghts)
  cmake_parse_arguments(PARSE_ARGV 0 A ""
    "WORK_DIR;SERIES;OUT_SRC_DIR;OUT_SOURCES;OUT_GENERATED;OUT_PATCHES" "ADAPTER_FILES")
  set(work "${A_WORK_DIR}")
  set(dest "${work}/src")
  set(stamp "${work}/source.stamp")
  set(manifest "${work}/source.manifest")
  get_filename_component(patch_dir "${A_SERIES}" DIRECTORY)

  if(NOT PATCH_EXECUTABLE OR NOT SH_EXECUTABLE)
    message(FATAL_ERROR "LIGGGHTS: `patch` and `sh` are needed; run scripts/setup.sh")
  endif()

  # --- the patch series ----------------------------------------------------------------------
  if(NOT EXISTS "${A_SERIES}")
    message(FATAL_ERROR "LIGGGHTS: patch series ${A_SERIES} is missing")
  endif()
  set_property(DIRECTORY "${PROJECT_SOURCE_DIR}" APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS "${A_SERIES}")
  file(STRINGS "${A_SERIES}" _lines)
  set(patches "")
  set(patch_names "")
  set(key "recipe ${_LG_RECIPE_VERSION}\n")
  foreach(_l IN LISTS _lines)
    string(STRIP "${_l}" _l)
    if(_l STREQUAL "" OR _l MATCHES "^#")
      continue()
    endif()
    set(_p "${patch_dir}/${_l}")
    if(NOT EXISTS "${_p}")
      message(FATAL_ERROR "LIGGGHTS: ${A_SERIES} lists `${_l}`, but ${_p} does not exist")
    endif()
    set_property(DIRECTORY "${PROJECT_SOURCE_DIR}" APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS "${_p}")
    file(SHA256 "${_p}" _h)
    string(APPEND key "patch ${_l} ${_h}\n")
    list(APPEND patches "${_p}")
    string(REGEX REPLACE "\\.(patch|diff)$" "" _n "${_l}")
    list(APPEND patch_names "${_n}")
  endforeach()

  # --- the pristine source -------------------------------------------------------------------
  if(LIGGGHTS_SOURCE_DIR)
    get_filename_component(_sd "${LIGGGHTS_SOURCE_DIR}" ABSOLUTE)
    if(NOT EXISTS "${_sd}/src/Make.sh")
      message(FATAL_ERROR "LIGGGHTS: LIGGGHTS_SOURCE_DIR=${_sd} has no src/Make.sh "
                          "(expected the top directory of a LIGGGHTS-PUBLIC-3.8.0 checkout)")
    endif()
    # Content hash of the checkout's src/ so that edits there are picked up at the next configure.
    file(GLOB_RECURSE _files LIST_DIRECTORIES false RELATIVE "${_sd}/src" "${_sd}/src/*")
    list(FILTER _files EXCLUDE REGEX "${_LG_EXCLUDE_REGEX}")
    list(SORT _files)
    set(_all "")
    foreach(_f IN LISTS _files)
      file(SHA1 "${_sd}/src/${_f}" _fh)
      string(APPEND _all "${_f} ${_fh}\n")
    endforeach()
    string(SHA256 _h "${_all}")
    string(APPEND key "source checkout ${_sd} ${_h}\n")
    message(STATUS "LIGGGHTS: source ${_sd}/src")
  else()
    if(NOT EXISTS "${LIGGGHTS_TARBALL}")
      message(FATAL_ERROR
        "LIGGGHTS: the source tarball ${LIGGGHTS_TARBALL} does not exist.\n"
        "Run scripts/setup.sh (it downloads and verifies it), or configure with "
        "-DLIGGGHTS_SOURCE_DIR=/path/to/LIGGGHTS-PUBLIC-3.8.0 or -DLIGGGHTS_TARBALL=/path/to/tarball, "
        "or -DSPACETREE_BUILD_LIGGGHTS=OFF to build only the core and its unit tests.")
    endif()
    set_property(DIRECTORY "${PROJECT_SOURCE_DIR}" APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS "${LIGGGHTS_TARBALL}")
    file(SHA256 "${LIGGGHTS_TARBALL}" _h)
    string(APPEND key "source tarball ${_h}\n")
    message(STATUS "LIGGGHTS: source ${LIGGGHTS_TARBALL}")
  endif()

  # --- copy + patch + sync (only when something changed) -------------------------------------
  set(_old_key "")
  if(EXISTS "${stamp}")
    file(READ "${stamp}" _old_key)
  endif()
  if(NOT _old_key STREQUAL key OR NOT EXISTS "${dest}/Make.sh" OR NOT EXISTS "${manifest}")
    message(STATUS "LIGGGHTS: preparing the patched source in ${dest}")
    set(stage "${work}/stage")
    file(REMOVE_RECURSE "${stage}" "${work}/extract")
    file(MAKE_DIRECTORY "${stage}")
    if(LIGGGHTS_SOURCE_DIR)
      file(COPY "${_sd}/src" DESTINATION "${stage}"
           REGEX "/Obj_[^/]*$" EXCLUDE
           REGEX "/src/style_[^/]*\\.(h|tmp)$" EXCLUDE
           REGEX "/src/style_contact_model\\.whitelist$" EXCLUDE
           REGEX "/src/version_liggghts\\.h$" EXCLUDE
           REGEX "\\.(o|d|a|so)$" EXCLUDE)
    else()
      file(MAKE_DIRECTORY "${work}/extract")
      execute_process(COMMAND "${CMAKE_COMMAND}" -E tar xf "${LIGGGHTS_TARBALL}"
                      WORKING_DIRECTORY "${work}/extract" RESULT_VARIABLE _rv ERROR_VARIABLE _err)
      file(GLOB _mk "${work}/extract/*/src/Make.sh")
      list(LENGTH _mk _n)
      if(NOT _rv EQUAL 0 OR NOT _n EQUAL 1)
        message(FATAL_ERROR "LIGGGHTS: extracting ${LIGGGHTS_TARBALL} failed or it has no */src/Make.sh: ${_err}")
      endif()
      get_filename_component(_top_src "${_mk}" DIRECTORY)
      file(RENAME "${_top_src}" "${stage}/src")
      file(REMOVE_RECURSE "${work}/extract")
    endif()

    foreach(_p IN LISTS patches)
      get_filename_component(_pn "${_p}" NAME)
      execute_process(
        COMMAND "${PATCH_EXECUTABLE}" -p1 --batch --forward --no-backup-if-mismatch -i "${_p}"
        WORKING_DIRECTORY "${stage}" RESULT_VARIABLE _rv OUTPUT_VARIABLE _out ERROR_VARIABLE _out)
      if(NOT _rv EQUAL 0)
        message(FATAL_ERROR "LIGGGHTS: applying liggghts_patch/${_pn} failed:\n${_out}")
      endif()
      message(STATUS "LIGGGHTS: applied ${_pn}")
    endforeach()

    # Sync stage/src -> dest by content; touched files get a fresh mtime so that they recompile.
    file(GLOB_RECURSE _new RELATIVE "${stage}/src" LIST_DIRECTORIES false "${stage}/src/*")
    list(SORT _new)
    if(EXISTS "${manifest}")
      file(STRINGS "${manifest}" _old)
      foreach(_f IN LISTS _old)
        if(NOT _f IN_LIST _new)
          file(REMOVE "${dest}/${_f}")
        endif()
      endforeach()
    endif()
    set(_changed 0)
    foreach(_f IN LISTS _new)
      set(_d "${dest}/${_f}")
      if(EXISTS "${_d}" AND NOT IS_SYMLINK "${_d}")
        file(SHA1 "${stage}/src/${_f}" _h1)
        file(SHA1 "${_d}" _h2)
        if(_h1 STREQUAL _h2)
          continue()
        endif()
      endif()
      file(REMOVE "${_d}")
      get_filename_component(_dd "${_d}" DIRECTORY)
      file(MAKE_DIRECTORY "${_dd}")
      file(RENAME "${stage}/src/${_f}" "${_d}")
      file(TOUCH_NOCREATE "${_d}")
      math(EXPR _changed "${_changed} + 1")
    endforeach()
    string(REPLACE ";" "\n" _manifest_text "${_new}")
    file(WRITE "${manifest}" "${_manifest_text}\n")
    file(REMOVE_RECURSE "${stage}")
    file(WRITE "${stamp}" "${key}")
    message(STATUS "LIGGGHTS: ${_changed} file(s) of ${dest} updated")
  endif()
  file(STRINGS "${manifest}" _lg_files)

  # --- symlinks to our adapter files ---------------------------------------------------------
  set(_adapter_names "")
  foreach(_f IN LISTS A_ADAPTER_FILES)
    get_filename_component(_n "${_f}" NAME)
    list(APPEND _adapter_names "${_n}")
    set(_l "${dest}/${_n}")
    if(_n IN_LIST _lg_files)
      message(FATAL_ERROR "LIGGGHTS: src/liggghts/${_n} has the name of a LIGGGHTS source file; "
                          "rename it (changes to LIGGGHTS files belong in liggghts_patch/)")
    endif()
    if(IS_SYMLINK "${_l}")
      file(READ_SYMLINK "${_l}" _t)
      if(_t STREQUAL _f)
        continue()
      endif()
      file(REMOVE "${_l}")
    elseif(EXISTS "${_l}")
      message(FATAL_ERROR "LIGGGHTS: src/liggghts/${_n} collides with the generated file ${_l}")
    endif()
    file(CREATE_LINK "${_f}" "${_l}" SYMBOLIC)
  endforeach()
  file(GLOB _entries LIST_DIRECTORIES true "${dest}/*")
  foreach(_e IN LISTS _entries)
    get_filename_component(_n "${_e}" NAME)
    if(IS_SYMLINK "${_e}" AND NOT _n IN_LIST _adapter_names AND NOT _n IN_LIST _lg_files)
      file(REMOVE "${_e}")   # adapter file that was removed or renamed
    endif()
  endforeach()

  # --- style headers -------------------------------------------------------------------------
  string(REPLACE ";" "," _patch_names_csv "${patch_names}")
  execute_process(
    COMMAND "${CMAKE_COMMAND}" "-DSRC_DIR=${dest}" "-DPATCH_NAMES=${_patch_names_csv}"
            -P "${CMAKE_CURRENT_FUNCTION_LIST_DIR}/LiggghtsGenerateHeaders.cmake"
    RESULT_VARIABLE _rv)
  if(NOT _rv EQUAL 0)
    message(FATAL_ERROR "LIGGGHTS: generating the style headers failed")
  endif()

  # --- results -------------------------------------------------------------------------------
  set(_sources "")
  foreach(_f IN LISTS _lg_files)
    if(_f MATCHES "^[^/]*\\.cpp$")
      list(APPEND _sources "${dest}/${_f}")
    endif()
  endforeach()
  file(GLOB _generated "${dest}/style_*.h")
  list(APPEND _generated "${dest}/version_liggghts.h")

  set(${A_OUT_SRC_DIR} "${dest}" PARENT_SCOPE)
  set(${A_OUT_SOURCES} "${_sources}" PARENT_SCOPE)
  set(${A_OUT_GENERATED} "${_generated}" PARENT_SCOPE)
  set(${A_OUT_PATCHES} "${_patch_names_csv}" PARENT_SCOPE)
endfunction()
