cmake_minimum_required(VERSION 3.25)
# A job never writes a file: in the application layer (app/) only the output files, app/outputs*
# and app/*_outputs (.cpp, .hpp), call what creates a folder or writes a file (create_directories,
# io::write..., writeTextFile, writeCsvFile, renderFigure, std::ofstream, fopen, an OutputFile or
# a DesignJournal); a job hands its files to a sink (app/outputs.hpp) or returns them for the
# front ends to write. Comments are left out of the search. Run with -DSOURCE_DIR=<tree>. With
# -DPLANT=<scratch folder>, the check instead copies app/ there, plants a write in a job's source
# and one in a job's header, and must then fail naming both: the test that shows the check can
# fail.
if(PLANT)
  file(REMOVE_RECURSE ${PLANT})
  file(COPY ${SOURCE_DIR}/app DESTINATION ${PLANT})
  file(APPEND ${PLANT}/app/workspace.cpp "void planted() { io::writeTextFile(\"x\", \"y\"); }\n")
  file(APPEND ${PLANT}/app/design.hpp "inline void planted() { std::ofstream out(\"x\"); }\n")
  execute_process(COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${PLANT} -P ${CMAKE_CURRENT_LIST_FILE}
                  RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
  file(REMOVE_RECURSE ${PLANT})
  if(result EQUAL 0)
    message(FATAL_ERROR "the output check passed app/workspace.cpp calling io::writeTextFile and app/design.hpp "
                        "opening a std::ofstream")
  endif()
  if(NOT err MATCHES "app/workspace.cpp: io::writeTextFile" OR NOT err MATCHES "app/design.hpp: ofstream")
    message(FATAL_ERROR "the output check failed, but did not name both planted writes:\n${err}")
  endif()
  message(STATUS "the planted writes were caught")
  return()
endif()

set(writes "create_director(y|ies)|io::write[A-Za-z]*|writeTextFile|writeCsvFile|renderFigure[A-Za-z]*|ofstream|fopen|OutputFile|DesignJournal")
file(GLOB files ${SOURCE_DIR}/app/*.cpp ${SOURCE_DIR}/app/*.hpp)
list(LENGTH files count)
if(count LESS 20)
  message(FATAL_ERROR "too few files found (${count} in app/): is SOURCE_DIR (${SOURCE_DIR}) the source tree?")
endif()
set(failures "")
set(outputs 0)
foreach(file IN LISTS files)
  get_filename_component(name ${file} NAME)
  if(name MATCHES "^(outputs[A-Za-z0-9_]*|[A-Za-z0-9_]+_outputs)\\.(cpp|hpp)$")
    math(EXPR outputs "${outputs} + 1")
    continue()
  endif()
  file(READ ${file} content)
  string(REPLACE ";" "," content "${content}")  # a list separator in CMake
  string(REGEX REPLACE "//[^\n]*" "" content "${content}")
  string(REGEX REPLACE "/\\*([^*]|\\*+[^*/])*\\*+/" "" content "${content}")
  string(REGEX MATCHALL "${writes}" found "${content}")
  if(found)
    list(REMOVE_DUPLICATES found)
    foreach(call IN LISTS found)
      list(APPEND failures "app/${name}: ${call}")
    endforeach()
  endif()
endforeach()
if(failures)
  string(REPLACE ";" "\n" text "${failures}")
  message(FATAL_ERROR "a job writes a file itself (only app/outputs* and app/*_outputs may; hand the file to a "
                      "sink, app/outputs.hpp):\n${text}")
endif()
message(STATUS "outputs: ${count} files of app/, ${outputs} of them output files, the only ones that write")
