# Tests of the 3-PRR in motion (direct kinematics, forward dynamics, control, operating envelope),
# included by tests/CMakeLists.txt.
nocdyn_add_test(direct_kinematics_test direct_kinematics_test.cpp)
nocdyn_add_test(forward_dynamics_test forward_dynamics_test.cpp)
foreach(source control_test envelope_test)
  if(EXISTS ${CMAKE_CURRENT_LIST_DIR}/${source}.cpp)
    nocdyn_add_test(${source} ${source}.cpp)
  endif()
endforeach()

# Against the independent Simbody model, when it is built.
if(TARGET nocdyn_simbody)
  nocdyn_add_test(simbody_simulation_test simbody_simulation_test.cpp
    LABELS validation LIBRARIES nocdyn_simbody_plant)
  nocdyn_add_test(simbody_plant_test simbody_plant_test.cpp LABELS validation LIBRARIES nocdyn_simbody)
  nocdyn_add_test(simbody_control_test simbody_control_test.cpp
    LABELS validation LIBRARIES nocdyn_simbody_plant)
endif()
nocdyn_add_test(forward_dynamics_robots_test forward_dynamics_robots_test.cpp)
nocdyn_add_test(control_robots_test control_robots_test.cpp)
