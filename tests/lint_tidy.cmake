# clang-tidy over one folder's files read as one translation unit, and each file's verdict
# (tests/CMakeLists.txt says why). Two modes:
#   -DMODE=folder -DTIDY=<clang-tidy> -DBUILD_DIR=<compile database> -DCONFIG=<.clang-tidy>
#       -DUNITY=<unity file> -DFILES=<a;b;...> -DLOG=<log>
#     runs clang-tidy on the unity file and keeps its output in LOG. It fails on a diagnostic in
#     no file of the folder (a header), on a crash, and on output it cannot attribute; a
#     diagnostic in one of the folder's files is left to that file's test.
#   -DMODE=file -DFILE=<file> -DLOG=<log>
#     fails, printing them, when the folder's run has diagnostics in FILE.
cmake_minimum_required(VERSION 3.20)

if(MODE STREQUAL "folder")
  file(REMOVE ${LOG})
  execute_process(COMMAND ${TIDY} -p ${BUILD_DIR} --quiet --config-file=${CONFIG} ${UNITY}
                  RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  # clang-tidy's own count of the diagnostics it left out (system headers) is not a finding
  string(REGEX REPLACE "[0-9]+ warnings? (and [0-9]+ errors? )?generated\\.\n?" "" err "${err}")
  set(text "${out}${err}")
  string(REGEX MATCHALL "[^\n]*: (warning|error): [^\n]*" diagnostics "${text}")
  set(elsewhere "")
  foreach(d IN LISTS diagnostics)
    set(ours OFF)
    foreach(f IN LISTS FILES)
      string(FIND "${d}" "${f}:" at)
      if(at EQUAL 0)
        set(ours ON)
      endif()
    endforeach()
    if(NOT ours)
      string(APPEND elsewhere "${d}\n")
    endif()
  endforeach()
  file(WRITE ${LOG}.partial "${text}")
  file(RENAME ${LOG}.partial ${LOG})
  list(LENGTH diagnostics count)
  message("clang-tidy on ${UNITY}: exit code ${code}, ${count} diagnostics (each file's test reports its own)")
  if(elsewhere)
    message(FATAL_ERROR "clang-tidy: diagnostics outside the folder's files (a header?):\n${elsewhere}\n${text}")
  endif()
  if(NOT code EQUAL 0 AND count EQUAL 0)
    message(FATAL_ERROR "clang-tidy failed (exit code ${code}) without a diagnostic:\n${text}")
  endif()
  # 1: diagnostics (left to the files' tests); anything else (a signal, a crash) may have cut the
  # run short, so that files after it were never checked
  if(NOT code EQUAL 0 AND NOT code EQUAL 1)
    message(FATAL_ERROR "clang-tidy stopped with ${code}: the folder's run is incomplete:\n${text}")
  endif()
elseif(MODE STREQUAL "file")
  if(NOT EXISTS ${LOG})
    message(FATAL_ERROR "no clang-tidy log ${LOG}: the folder's run did not complete")
  endif()
  file(STRINGS ${LOG} lines)
  set(found "")
  set(left 0)
  foreach(line IN LISTS lines)
    string(FIND "${line}" "${FILE}:" at)
    if(at EQUAL 0 AND line MATCHES ": (warning|error): ")
      set(left 3)  # the diagnostic and its source line and caret
    endif()
    if(left GREATER 0)
      string(APPEND found "${line}\n")
      math(EXPR left "${left} - 1")
    endif()
  endforeach()
  if(found)
    if(found MATCHES "clang-diagnostic-error")
      string(APPEND found "(the folder's files are read as one translation unit: a name local to one file must not "
                          "be defined again by another file of the folder)\n")
    endif()
    message(FATAL_ERROR "clang-tidy:\n${found}")
  endif()
  message("clang-tidy: nothing in ${FILE}")
else()
  message(FATAL_ERROR "MODE must be folder or file")
endif()
