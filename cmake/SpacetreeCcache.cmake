# Use ccache as compiler launcher when found (and not already chosen by the user).
# Cache location/size are ccache's own settings (CCACHE_DIR, CCACHE_MAXSIZE; scripts/build.sh sets sane defaults).
if(SPACETREE_USE_CCACHE)
  find_program(CCACHE_PROGRAM ccache)
  if(CCACHE_PROGRAM)
    foreach(_lang C CXX)
      if(NOT CMAKE_${_lang}_COMPILER_LAUNCHER)   # a user's -DCMAKE_CXX_COMPILER_LAUNCHER=... wins
        set(CMAKE_${_lang}_COMPILER_LAUNCHER "${CCACHE_PROGRAM}")
      endif()
    endforeach()
    message(STATUS "spacetree-dem: using ccache (${CCACHE_PROGRAM})")
  else()
    message(STATUS "spacetree-dem: ccache not found, compiling without it")
  endif()
endif()
