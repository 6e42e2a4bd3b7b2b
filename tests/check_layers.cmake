cmake_minimum_required(VERSION 3.25)
# The layers depend only downwards, and the folder is the layer:
#   core      src/core, include/nocdyn/*.hpp, include/nocdyn/detail   (Eigen only)
#   analysis  src/analysis, include/nocdyn/analysis                   over core
#   sim       src/sim, include/nocdyn/sim                             over core, analysis
#   io        src/io, include/nocdyn/io                               over core only
#   tables    src/tables, include/nocdyn/tables                       over every layer above
#   validation  validation/ (the Simbody and MuJoCo models, SimbodyPlant)  over the library
#   render    render/ (figures, the animation page; no CLI11)         over core, analysis, io, tables: no sim
#   app       app/ (each command's options, run and typed result)     over all of the above
# apps/ (the command line) and python/ stand on all of them.
# A file may include a library header ("nocdyn/...") only of its own layer or one it stands on. The
# private headers of a folder (src/core/stages.hpp, ...) count as that folder's layer; render's
# headers ("render/plot.hpp") are render's layer and the application layer's ("app/pose.hpp")
# app's; nothing in the library includes render's or the CLI's headers or CLI11, and render
# includes no header of sim/ (its figures take what the layers under it compute) nor of app/.
# Run with -DSOURCE_DIR=<tree>. With -DPLANT=<scratch folder>, the check instead copies the
# tree's library folders there, plants four upward includes (sim in a core file, sim and the
# application layer in a render file, a private header in python/) and must then fail naming each: the test that shows the
# check can fail.
if(PLANT)
  file(REMOVE_RECURSE ${PLANT})
  foreach(dir src include render app apps validation python)
    file(COPY ${SOURCE_DIR}/${dir} DESTINATION ${PLANT})
  endforeach()
  file(APPEND ${PLANT}/src/core/model.cpp "#include \"nocdyn/sim/shake.hpp\"\n")
  file(APPEND ${PLANT}/render/plot.cpp "#include \"nocdyn/sim/shake_replay.hpp\"\n#include \"app/shake.hpp\"\n")
  file(APPEND ${PLANT}/python/src/module.cpp "#include \"../../src/core/stages.hpp\"\n")
  execute_process(COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${PLANT} -P ${CMAKE_CURRENT_LIST_FILE}
                  RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
  file(REMOVE_RECURSE ${PLANT})
  if(result EQUAL 0)
    message(FATAL_ERROR "the layer check passed a core file that includes nocdyn/sim/shake.hpp and a render "
                        "file that includes nocdyn/sim/shake_replay.hpp and app/shake.hpp")
  endif()
  foreach(planted "src/core/model.cpp: core includes nocdyn/sim/shake.hpp"
                  "render/plot.cpp: render includes nocdyn/sim/shake_replay.hpp"
                  "render/plot.cpp: render includes the application layer's app/shake.hpp"
                  "python/src/module.cpp: python includes the private header")
    if(NOT err MATCHES "${planted}")
      message(FATAL_ERROR "the layer check failed, but did not name the planted include (${planted}):\n${err}")
    endif()
  endforeach()
  message(STATUS "the planted upward includes were caught: ${err}")
  return()
endif()

# the layers each layer may include (its own among them)
set(allowed_core core)
set(allowed_analysis core analysis)
set(allowed_sim core analysis sim)
set(allowed_io core io)
set(allowed_tables core analysis sim io tables)
set(allowed_validation core analysis sim io tables validation)
set(allowed_render core analysis io tables render)
set(allowed_app core analysis sim io tables validation render app)
# the layer of a library header named in an #include "nocdyn/..."
function(header_layer header out)
  if(header MATCHES "^nocdyn/(analysis|sim|io|tables|validation)/")
    set(${out} ${CMAKE_MATCH_1} PARENT_SCOPE)
  elseif(header MATCHES "^nocdyn/[a-z0-9_]+/" AND NOT header MATCHES "^nocdyn/detail/")
    set(${out} other PARENT_SCOPE)  # e.g. the frozen benchmark kernel (nocdyn/prr3): no library file uses it
  else()
    set(${out} core PARENT_SCOPE)
  endif()
endfunction()

file(GLOB cli_headers RELATIVE ${SOURCE_DIR}/apps/nocdyn ${SOURCE_DIR}/apps/nocdyn/*.hpp)
file(GLOB render_headers RELATIVE ${SOURCE_DIR}/render ${SOURCE_DIR}/render/*.hpp)
set(failures "")
set(counts "")
function(check layer globs)
  set(files "")
  foreach(glob IN LISTS globs)
    file(GLOB found ${SOURCE_DIR}/${glob})
    list(APPEND files ${found})
  endforeach()
  list(LENGTH files count)
  set(counts "${counts} ${count} ${layer}" PARENT_SCOPE)
  foreach(file IN LISTS files)
    file(RELATIVE_PATH name ${SOURCE_DIR} ${file})
    file(STRINGS ${file} includes REGEX "^#include [\"<]")
    foreach(line IN LISTS includes)
      string(REGEX REPLACE "^#include [\"<]([^\">]+)[\">].*" "\\1" header "${line}")
      if(header MATCHES "^\\.\\./(core|analysis|sim|io|tables)/")
        # a private header of another folder, by a relative path: that folder's layer
        if(NOT CMAKE_MATCH_1 IN_LIST allowed_${layer})
          list(APPEND failures "${name}: ${layer} includes ${header}")
        endif()
      elseif(header MATCHES "^app/")
        # the application layer's headers ("app/pose.hpp"): above the library and render
        if(NOT "app" IN_LIST allowed_${layer})
          list(APPEND failures "${name}: ${layer} includes the application layer's ${header}")
        endif()
      elseif(header MATCHES "^render/")
        # the rendering layer's headers ("render/plot.hpp"): above the library
        if(NOT "render" IN_LIST allowed_${layer})
          list(APPEND failures "${name}: ${layer} includes the rendering layer's ${header}")
        endif()
      elseif(header MATCHES "^nocdyn/")
        header_layer(${header} target)
        if(NOT target IN_LIST allowed_${layer})
          list(APPEND failures "${name}: ${layer} includes ${header}")
        endif()
      elseif(header MATCHES "^CLI/" OR header IN_LIST cli_headers)
        list(APPEND failures "${name}: ${layer} includes the command line's ${header}")
      elseif(NOT layer MATCHES "^(render|app)$" AND header IN_LIST render_headers)
        list(APPEND failures "${name}: ${layer} includes render's ${header}")
      endif()
    endforeach()
  endforeach()
  set(failures ${failures} PARENT_SCOPE)
endfunction()
check(core "src/core/*.cpp;src/core/*.hpp;include/nocdyn/*.hpp;include/nocdyn/detail/*.hpp")
check(analysis "src/analysis/*.cpp;src/analysis/*.hpp;include/nocdyn/analysis/*.hpp")
check(sim "src/sim/*.cpp;src/sim/*.hpp;include/nocdyn/sim/*.hpp")
check(io "src/io/*.cpp;src/io/*.hpp;include/nocdyn/io/*.hpp")
check(tables "src/tables/*.cpp;src/tables/*.hpp;include/nocdyn/tables/*.hpp")
check(validation "validation/src/*.cpp;validation/*/src/*.cpp;validation/*/src/*.hpp;validation/include/nocdyn/validation/*.hpp;validation/include/nocdyn/validation/detail/*.hpp;validation/*/include/nocdyn/validation/*.hpp")
check(render "render/*.cpp;render/*.hpp")
check(app "app/*.cpp;app/*.hpp")
# python/ (the compiled module) binds the library's public headers (nocdyn/...), the application
# layer (app/) and render's; the command line's headers only in its CLI entry (cli_main.cpp, for
# `python -m nocdyn`); never a private header of a folder (src/..., by a relative path).
file(GLOB python_files ${SOURCE_DIR}/python/src/*.cpp ${SOURCE_DIR}/python/src/*.hpp)
file(GLOB python_own RELATIVE ${SOURCE_DIR}/python/src ${SOURCE_DIR}/python/src/*.hpp)
list(LENGTH python_files count)
set(counts "${counts} ${count} python")
foreach(file IN LISTS python_files)
  file(RELATIVE_PATH name ${SOURCE_DIR} ${file})
  file(STRINGS ${file} includes REGEX "^#include \"")
  foreach(line IN LISTS includes)
    string(REGEX REPLACE "^#include \"([^\"]+)\".*" "\\1" header "${line}")
    if(header MATCHES "^nocdyn/|^app/|^render/|^pybind11/" OR header IN_LIST python_own)
      continue()
    elseif(header IN_LIST cli_headers AND name STREQUAL "python/src/cli_main.cpp")
      continue()
    elseif(header IN_LIST cli_headers)
      list(APPEND failures "${name}: python includes the command line's ${header} (only cli_main.cpp may)")
    elseif(header IN_LIST render_headers)
      continue()  # render's headers by their bare name (render/ is on the module's include path)
    else()
      list(APPEND failures "${name}: python includes the private header ${header}")
    endif()
  endforeach()
endforeach()
# Nothing of the library lies outside its layer folders.
file(GLOB loose ${SOURCE_DIR}/src/*.cpp ${SOURCE_DIR}/src/*.hpp)
foreach(file IN LISTS loose)
  list(APPEND failures "${file}: a source directly under src/ is in no layer (src/core, analysis, sim, io, tables)")
endforeach()
if(failures)
  string(REPLACE ";" "\n" text "${failures}")
  message(FATAL_ERROR "layers depend upwards:\n${text}")
endif()
string(REGEX MATCHALL "[0-9]+ [a-z]+" pairs "${counts}")
foreach(pair IN LISTS pairs)
  string(REGEX MATCH "^[0-9]+" n "${pair}")
  if(n LESS 3)
    message(FATAL_ERROR "too few files found (${pair}): is SOURCE_DIR (${SOURCE_DIR}) the source tree?")
  endif()
endforeach()
message(STATUS "layers:${counts} files include no header above their layer")
