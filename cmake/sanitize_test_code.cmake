# Under the sanitizers (NOCDYN_SANITIZE), the code that drives the library (the tests in
# tests/, the application layer in app/, the command line in apps/nocdyn, the rendering module in
# render/) and the independent engines' models with their tests (validation/, whose Simbody and
# MuJoCo code checks the library and is not the library) are compiled at -Og (GCC) or -O0 (clang,
# whose -Og is its -O1) instead of the library's -O1: the same instrumentation and checks
# (-fsanitize=address,undefined, no recovery), at about half the compile time of -O1 with ASan and
# UBSan (GCC: cmd_shake.cpp 23 s of CPU at -O1, 12 s at -Og; validation's mujoco_spatial.cpp
# 39.7 s at -O1, 23.4 s at -Og; clang: tests/reactions_test.cpp 29.9 s at -O1, 15.1 s at -O0),
# while the library, where the tests spend their time, keeps -O1. Every target of those folders is
# covered, so that a new test or command is too. Included by the top-level CMakeLists.txt after
# those folders.
get_property(subdirectories DIRECTORY ${PROJECT_SOURCE_DIR} PROPERTY SUBDIRECTORIES)
set(test_code_dirs tests app apps/nocdyn render)
if(${PROJECT_SOURCE_DIR}/validation IN_LIST subdirectories)
  list(APPEND test_code_dirs validation)
  get_property(validation_dirs DIRECTORY ${PROJECT_SOURCE_DIR}/validation PROPERTY SUBDIRECTORIES)
  list(APPEND subdirectories ${validation_dirs})  # validation/simbody, validation/mujoco
  foreach(dir IN LISTS validation_dirs)
    file(RELATIVE_PATH dir ${PROJECT_SOURCE_DIR} ${dir})
    list(APPEND test_code_dirs ${dir})
  endforeach()
endif()
foreach(dir IN LISTS test_code_dirs)
  if(NOT ${PROJECT_SOURCE_DIR}/${dir} IN_LIST subdirectories)
    continue()  # not built in this configuration
  endif()
  get_property(targets DIRECTORY ${PROJECT_SOURCE_DIR}/${dir} PROPERTY BUILDSYSTEM_TARGETS)
  foreach(target IN LISTS targets)
    get_target_property(type ${target} TYPE)
    if(type STREQUAL "EXECUTABLE" OR type STREQUAL "STATIC_LIBRARY")
      # after the directory's -O1 on the command line, so that it takes effect
      set_property(TARGET ${target} APPEND PROPERTY COMPILE_OPTIONS $<IF:$<CXX_COMPILER_ID:Clang>,-O0,-Og>
                                                                    $<$<CXX_COMPILER_ID:GNU>:-fno-inline-small-functions>)
      # The tests and the engines' models without line tables (-g0 after the directory's -g1):
      # a sanitizer's report names their frames by function, and keeps file:line in the
      # library's, the application layer's and the command line's frames, where the code under
      # test is. GCC compiles a test file in 10-20 % less CPU without them
      # (tests/cli_reactions_test.cpp 15.3 s -> 12.2 s, tests/spatial_dynamics_test.cpp
      # 18.6 s -> 16.5 s).
      if(dir STREQUAL "tests" OR dir MATCHES "^validation")
        set_property(TARGET ${target} APPEND PROPERTY COMPILE_OPTIONS -g0)
      endif()
    endif()
  endforeach()
endforeach()
