#include "mpi_cluster.h"

#include "trac0r/accumulator_merge.h"

#include <mpi.h>

#include <algorithm>
#include <stdexcept>

namespace trac0r_viewer {

namespace {

void check(int status, const char* what) {
    if (status != MPI_SUCCESS) {
        throw std::runtime_error(std::string("MPI: ") + what + " failed (error " +
                                 std::to_string(status) + ")");
    }
}

template <typename T>
std::vector<T> all_gather(const T& mine, int ranks) {
    std::vector<T> all(static_cast<std::size_t>(ranks));
    check(
        MPI_Allgather(&mine, sizeof(T), MPI_BYTE, all.data(), sizeof(T), MPI_BYTE, MPI_COMM_WORLD),
        "MPI_Allgather");
    return all;
}

}  // namespace

MpiCluster::MpiCluster() {
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
    MPI_Comm node;
    if (MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node) ==
        MPI_SUCCESS) {
        MPI_Comm_rank(node, &local_rank_);
        MPI_Comm_free(&node);
    }
}

std::vector<trac0r::RoundReport> MpiCluster::exchange(const trac0r::RoundReport& mine) {
    return all_gather(mine, size_);
}

std::vector<StartReport> MpiCluster::start(const StartReport& mine) {
    return all_gather(mine, size_);
}

void MpiCluster::merge_to_first(std::vector<trac0r::kernel::AccumPixel>& accumulator) {
    using trac0r::kernel::AccumPixel;
    const std::size_t chunk = 16384;
    const std::size_t pixels = accumulator.size();
    std::vector<AccumPixel> gathered(rank_ == 0 ? chunk * static_cast<std::size_t>(size_) : 0);
    for (std::size_t begin = 0; begin < pixels; begin += chunk) {
        const std::size_t count = std::min(chunk, pixels - begin);
        const int bytes = static_cast<int>(count * sizeof(AccumPixel));
        check(MPI_Gather(accumulator.data() + begin, bytes, MPI_BYTE, gathered.data(), bytes,
                         MPI_BYTE, 0, MPI_COMM_WORLD),
              "MPI_Gather(accumulator)");
        if (rank_ == 0) {
            std::vector<const AccumPixel*> parts;
            for (int r = 0; r < size_; ++r) {
                parts.push_back(gathered.data() + static_cast<std::size_t>(r) * count);
            }
            trac0r::merge_accumulators(parts, count, accumulator.data() + begin);
        }
    }
    merged_ = true;
}

}  // namespace trac0r_viewer
