
# Consider dependencies only in project.
set(CMAKE_DEPENDS_IN_PROJECT_ONLY OFF)

# The set of languages for which implicit dependencies are needed:
set(CMAKE_DEPENDS_LANGUAGES
  )

# The set of dependency files which are needed:
set(CMAKE_DEPENDS_DEPENDENCY_FILES
  "/work/main/src/io/csv.cpp" "CMakeFiles/nocdyn.dir/src/io/csv.cpp.o" "gcc" "CMakeFiles/nocdyn.dir/src/io/csv.cpp.o.d"
  "/work/main/src/io/robot_yaml.cpp" "CMakeFiles/nocdyn.dir/src/io/robot_yaml.cpp.o" "gcc" "CMakeFiles/nocdyn.dir/src/io/robot_yaml.cpp.o.d"
  "/work/main/src/io/trajectory_yaml.cpp" "CMakeFiles/nocdyn.dir/src/io/trajectory_yaml.cpp.o" "gcc" "CMakeFiles/nocdyn.dir/src/io/trajectory_yaml.cpp.o.d"
  "/work/main/src/io/yaml_util.cpp" "CMakeFiles/nocdyn.dir/src/io/yaml_util.cpp.o" "gcc" "CMakeFiles/nocdyn.dir/src/io/yaml_util.cpp.o.d"
  "/work/main/src/prr3/dynamics.cpp" "CMakeFiles/nocdyn.dir/src/prr3/dynamics.cpp.o" "gcc" "CMakeFiles/nocdyn.dir/src/prr3/dynamics.cpp.o.d"
  "/work/main/src/prr3/kinematics.cpp" "CMakeFiles/nocdyn.dir/src/prr3/kinematics.cpp.o" "gcc" "CMakeFiles/nocdyn.dir/src/prr3/kinematics.cpp.o.d"
  "/work/main/src/prr3/model.cpp" "CMakeFiles/nocdyn.dir/src/prr3/model.cpp.o" "gcc" "CMakeFiles/nocdyn.dir/src/prr3/model.cpp.o.d"
  "/work/main/src/prr3/sampling.cpp" "CMakeFiles/nocdyn.dir/src/prr3/sampling.cpp.o" "gcc" "CMakeFiles/nocdyn.dir/src/prr3/sampling.cpp.o.d"
  "/work/main/src/robot.cpp" "CMakeFiles/nocdyn.dir/src/robot.cpp.o" "gcc" "CMakeFiles/nocdyn.dir/src/robot.cpp.o.d"
  "/work/main/src/status.cpp" "CMakeFiles/nocdyn.dir/src/status.cpp.o" "gcc" "CMakeFiles/nocdyn.dir/src/status.cpp.o.d"
  "/work/main/src/trajectory.cpp" "CMakeFiles/nocdyn.dir/src/trajectory.cpp.o" "gcc" "CMakeFiles/nocdyn.dir/src/trajectory.cpp.o.d"
  )

# Targets to which this target links.
set(CMAKE_TARGET_LINKED_INFO_FILES
  )

# Fortran module output directory.
set(CMAKE_Fortran_TARGET_MODULE_DIR "")
