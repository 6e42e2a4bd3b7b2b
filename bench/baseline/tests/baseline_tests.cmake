# The frozen 3-PRR kernel (bench/baseline) is the benchmarks' speed baseline only. One test keeps
# the comparison honest: the baseline and the general model compute the same numbers, so the
# ratio the benchmarks print is the cost of generality and nothing else. Registered by
# tests/CMakeLists.txt with its nocdyn_add_test (ctest -L baseline).
nocdyn_add_test(baseline_equals_model_test
                ${PROJECT_SOURCE_DIR}/bench/baseline/tests/equals_model_test.cpp
                LABELS baseline LIBRARIES nocdyn_prr3_baseline)
