// communicator.h — the ranks of a render spread over processes (MPI) or threads, as the render
// session sees them: who am I, how many are we, and the few collective operations the sessions
// need. Every collective must be called by every rank, in the same order, with the same sizes.
//
// One process renders alone with singleProcess(); an MPI run (distributed/mpi/, built when MPI is
// found) and the in-process group of tests (in_process_group.h) implement the same interface, so
// the sessions hold one code path whatever carries the bytes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace caustica {

class Communicator {
public:
    virtual ~Communicator() = default;

    virtual int rank() const = 0;
    virtual int size() const = 0;
    bool isRoot() const { return rank() == 0; }

    /// Element-wise sums over all ranks, left in `values` on every rank. The sum is taken in rank
    /// order (rank 0 + rank 1 + ...), so every rank holds the same bits, run after run.
    virtual void sum(std::span<double> values) = 0;
    virtual void sum(std::span<float> values) = 0;
    virtual void sum(std::span<uint64_t> values) = 0;
    /// The largest of every rank's `value`.
    virtual double max(double value) = 0;
    /// Every rank's `bytes`, indexed by rank (sizes may differ between ranks).
    virtual std::vector<std::vector<uint8_t>> allGather(std::span<const uint8_t> bytes) = 0;
    /// `root`'s `bytes` on every rank (resized to fit).
    virtual void broadcast(std::vector<uint8_t>& bytes, int root) = 0;
    virtual void barrier() = 0;

    /// Bytes this rank has sent so far (0 for a single process).
    virtual uint64_t bytesSent() const = 0;
    /// Collective operations this rank has taken part in so far (each a meeting of all ranks:
    /// every rank waits for the slowest); 0 for a single process.
    virtual uint64_t collectives() const = 0;

    /// Whether any rank passes true.
    bool any(bool flag) { return max(flag ? 1.0 : 0.0) > 0; }
    /// Agrees on failure: every rank passes its error message ("" when it has none) and gets
    /// "rank R: MESSAGE" of the lowest failing rank, or "" when no rank failed.
    std::string firstError(const std::string& message);
};

/// The communicator of a render in one process: rank 0 of 1; collectives leave values unchanged.
Communicator& singleProcess();

}  // namespace caustica
