file(REMOVE_RECURSE
  "CMakeFiles/nocdyn.dir/src/io/csv.cpp.o"
  "CMakeFiles/nocdyn.dir/src/io/csv.cpp.o.d"
  "CMakeFiles/nocdyn.dir/src/io/robot_yaml.cpp.o"
  "CMakeFiles/nocdyn.dir/src/io/robot_yaml.cpp.o.d"
  "CMakeFiles/nocdyn.dir/src/io/trajectory_yaml.cpp.o"
  "CMakeFiles/nocdyn.dir/src/io/trajectory_yaml.cpp.o.d"
  "CMakeFiles/nocdyn.dir/src/io/yaml_util.cpp.o"
  "CMakeFiles/nocdyn.dir/src/io/yaml_util.cpp.o.d"
  "CMakeFiles/nocdyn.dir/src/prr3/dynamics.cpp.o"
  "CMakeFiles/nocdyn.dir/src/prr3/dynamics.cpp.o.d"
  "CMakeFiles/nocdyn.dir/src/prr3/kinematics.cpp.o"
  "CMakeFiles/nocdyn.dir/src/prr3/kinematics.cpp.o.d"
  "CMakeFiles/nocdyn.dir/src/prr3/model.cpp.o"
  "CMakeFiles/nocdyn.dir/src/prr3/model.cpp.o.d"
  "CMakeFiles/nocdyn.dir/src/prr3/sampling.cpp.o"
  "CMakeFiles/nocdyn.dir/src/prr3/sampling.cpp.o.d"
  "CMakeFiles/nocdyn.dir/src/robot.cpp.o"
  "CMakeFiles/nocdyn.dir/src/robot.cpp.o.d"
  "CMakeFiles/nocdyn.dir/src/status.cpp.o"
  "CMakeFiles/nocdyn.dir/src/status.cpp.o.d"
  "CMakeFiles/nocdyn.dir/src/trajectory.cpp.o"
  "CMakeFiles/nocdyn.dir/src/trajectory.cpp.o.d"
  "libnocdyn.a"
  "libnocdyn.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang CXX)
  include(CMakeFiles/nocdyn.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
