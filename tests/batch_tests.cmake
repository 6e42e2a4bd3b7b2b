# Batch inverse dynamics: equal to the per-sample path, one thread or many.
nocdyn_add_test(batch_test batch_test.cpp)
# The lean per-sample entry (fast.hpp): equal to the full path, same Status, allocation-free.
nocdyn_add_test(fast_test fast_test.cpp)
