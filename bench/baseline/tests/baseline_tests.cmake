# Tests of the frozen 3-PRR kernel (bench/baseline, ctest -L baseline), registered by
# tests/CMakeLists.txt with its nocdyn_add_test.
set(NOCDYN_BASELINE_TESTS ${PROJECT_SOURCE_DIR}/bench/baseline/tests)
# Batch inverse dynamics: equal to the per-sample path, one thread or many.
nocdyn_add_test(baseline_batch_test ${NOCDYN_BASELINE_TESTS}/batch_test.cpp LABELS baseline
                LIBRARIES nocdyn_prr3_baseline)
# The lean per-sample entry (fast.hpp): equal to the full path, same Status, allocation-free.
nocdyn_add_test(baseline_fast_test ${NOCDYN_BASELINE_TESTS}/fast_test.cpp LABELS baseline
                LIBRARIES nocdyn_prr3_baseline)
# Appendix A and eqs. 6-7 as the paper writes them.
nocdyn_add_test(baseline_paper_formulas_test ${NOCDYN_BASELINE_TESTS}/paper_formulas_test.cpp LABELS baseline
                LIBRARIES nocdyn_prr3_baseline)
# The baseline and the general model compute the same numbers (what the speed ratio compares).
nocdyn_add_test(baseline_equals_general_model_test ${NOCDYN_BASELINE_TESTS}/equals_general_model_test.cpp
                LABELS baseline LIBRARIES nocdyn_prr3_baseline)
# The paper's trajectories against the golden values, as tests/golden_test.cpp on the general model.
nocdyn_add_test(baseline_golden_test ${NOCDYN_BASELINE_TESTS}/golden_test.cpp LABELS baseline
                LIBRARIES nocdyn_prr3_baseline)
# The baseline against its own 3-PRR engine models (Simbody, MuJoCo): forces and inertia.
if(TARGET nocdyn_prr3_simbody AND TARGET nocdyn_prr3_mujoco)
  nocdyn_add_test(baseline_engines_agreement_test ${NOCDYN_BASELINE_TESTS}/engines_agreement_test.cpp
                  LABELS validation baseline LIBRARIES nocdyn_prr3_simbody nocdyn_prr3_mujoco nocdyn_prr3_baseline)
endif()
