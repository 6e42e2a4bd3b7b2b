// The batch's packets of eight samples (batch_chunk.hpp), one AVX-512 register per quantity.
// This file alone is compiled for x86-64-v4 (CMakeLists.txt), so that every function the
// kernel inlines, and its lane masks, are built for it: GCC 12 lowers a 512-bit comparison
// or select written in a function compiled for an older target to one lane at a time, even
// where it is inlined into an x86-64-v4 function. batch.cpp calls it only where the CPU has
// x86-64-v4 (batchPacketWidth). Nothing here has external linkage but chunk8, and the test
// `batch_avx512.object_defines_only_chunk8` checks that the object defines no other symbol
// (an inline function compiled here must not replace another file's copy).
#include "batch_chunk.hpp"

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace nocdyn::detail {

BatchResult chunk8(const Model& model, const BatchArrays& a, Eigen::Index begin, Eigen::Index end) {
    return chunkOf<fastmath::Pack8>(model, a, begin, end);
}

}  // namespace nocdyn::detail
