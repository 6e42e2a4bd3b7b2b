# Batch inverse dynamics (issue 5): equal to the per-sample path, one thread or many.
nocdyn_add_test(batch_test batch_test.cpp)
