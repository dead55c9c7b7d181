// The processes one batch render is split across: one (trac0r_viewer), or
// the MPI ranks of trac0r_mpi (mpi_cluster.h). run_batch asks it what the
// others did after every round of frames, so that every rank decides the
// same, and merges the accumulators at the end.
#ifndef TRAC0R_VIEWER_CLUSTER_H
#define TRAC0R_VIEWER_CLUSTER_H

#include "trac0r/kernel/types.h"

#include <cstdint>
#include <vector>

namespace trac0r_viewer {

// What a rank tells the others after a round of frames.
struct RoundReport {
    std::int32_t signal = 0;      // SIGINT or SIGTERM received, else 0
    std::int32_t overflowed = 0;  // its noise estimate has overflowed float
    std::int64_t frames = 0;      // frames it has rendered
    double elapsed = 0.0;         // seconds since its render started
    double estimate = 0.0;        // its noise estimate, where the round asks for one
};

class Cluster {
  public:
    virtual ~Cluster() = default;
    virtual int rank() const = 0;
    virtual int size() const = 0;
    // Every rank's report, in rank order, on every rank (a collective: each
    // rank calls it once a round).
    virtual std::vector<RoundReport> exchange(const RoundReport& mine) = 0;
    // Rank 0's `accumulator` becomes the merge of every rank's (in rank
    // order, accumulator_merge.h); the other ranks' are sent and left as
    // they were. A collective.
    virtual void merge_to_first(std::vector<trac0r::kernel::AccumPixel>& accumulator) = 0;
};

// One process: the render as it always was.
class SingleProcess : public Cluster {
  public:
    int rank() const override { return 0; }
    int size() const override { return 1; }
    std::vector<RoundReport> exchange(const RoundReport& mine) override { return {mine}; }
    void merge_to_first(std::vector<trac0r::kernel::AccumPixel>&) override {}
};

}  // namespace trac0r_viewer

#endif
