// Accumulators of one image over disjoint sets of frames (the ranks of a
// split render, trac0r_mpi) combined into the accumulator of all of them:
// the sums added and the luminance moments merged (Chan, Golub and LeVeque's
// pairwise update of Welford's), in double, in the order the parts are
// given, so that the same parts always give the same bits.
#ifndef TRAC0R_ACCUMULATOR_MERGE_H
#define TRAC0R_ACCUMULATOR_MERGE_H

#include "trac0r/kernel/types.h"

#include <cstddef>
#include <vector>

namespace trac0r {

// out[i], for i < pixels, from parts[0][i], parts[1][i], ... in that order.
// The merged sum is exact to double before it is rounded to float once
// (its compensation then holds the rounding), where one accumulator over
// all frames rounds at every frame with Kahan's correction: the two agree
// to a few float ulps of the mean.
void merge_accumulators(const std::vector<const kernel::AccumPixel*>& parts, std::size_t pixels,
                        kernel::AccumPixel* out);

}  // namespace trac0r

#endif
