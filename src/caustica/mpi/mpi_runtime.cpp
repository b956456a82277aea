#include "caustica/mpi/mpi_runtime.h"

#include <mpi.h>

#include <algorithm>
#include <climits>
#include <cstdlib>
#include <string>
#include <vector>

#include "caustica/util/error.h"

namespace caustica {
namespace {

void check(int code, const char* what) {
    if (code == MPI_SUCCESS) return;
    char text[MPI_MAX_ERROR_STRING];
    int length = 0;
    MPI_Error_string(code, text, &length);
    throw Error(std::string("MPI ") + what + " failed: " + std::string(text, size_t(length)));
}

int count(size_t bytes, const char* what) {
    if (bytes > size_t(INT_MAX)) throw Error(std::string("MPI ") + what + ": more than 2 GiB in one message");
    return int(bytes);
}

template <class T>
MPI_Datatype datatype();
template <>
MPI_Datatype datatype<double>() { return MPI_DOUBLE; }
template <>
MPI_Datatype datatype<float>() { return MPI_FLOAT; }
template <>
MPI_Datatype datatype<uint64_t>() { return MPI_UINT64_T; }

/// MPI_COMM_WORLD. Sums are gathered to rank 0, added there in rank order and broadcast: the same
/// bits on every rank and in every run, whatever reduction algorithm the MPI library would pick
/// (MPI_Reduce may associate in any order). bytesSent counts what this rank hands to MPI for
/// other ranks: a broadcast's root counts its message once per receiver.
class MpiWorld final : public Communicator {
public:
    MpiWorld() {
        MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
        MPI_Comm_size(MPI_COMM_WORLD, &size_);
    }
    int rank() const override { return rank_; }
    int size() const override { return size_; }
    void sum(std::span<double> v) override { sumInRankOrder(v); }
    void sum(std::span<float> v) override { sumInRankOrder(v); }
    void sum(std::span<uint64_t> v) override { sumInRankOrder(v); }
    double max(double value) override {
        double result = value;  // the maximum does not depend on the order
        ++collectives_;
        check(MPI_Allreduce(&value, &result, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD), "allreduce");
        sent_ += sizeof(double);
        return result;
    }
    std::vector<std::vector<uint8_t>> allGather(std::span<const uint8_t> bytes) override {
        int mine = count(bytes.size(), "allgather");
        ++collectives_;
        std::vector<int> sizes(static_cast<size_t>(size_), 0), offsets(static_cast<size_t>(size_), 0);
        check(MPI_Allgather(&mine, 1, MPI_INT, sizes.data(), 1, MPI_INT, MPI_COMM_WORLD), "allgather");
        size_t total = 0;
        for (int r = 0; r < size_; ++r) {
            offsets[size_t(r)] = count(total, "allgather");
            total += size_t(sizes[size_t(r)]);
        }
        count(total, "allgather");
        std::vector<uint8_t> all(std::max<size_t>(total, 1));
        check(MPI_Allgatherv(bytes.data(), mine, MPI_BYTE, all.data(), sizes.data(), offsets.data(), MPI_BYTE,
                             MPI_COMM_WORLD),
              "allgatherv");
        sent_ += (sizeof(int) + bytes.size()) * uint64_t(size_ - 1);
        std::vector<std::vector<uint8_t>> parts(static_cast<size_t>(size_), std::vector<uint8_t>{});
        for (int r = 0; r < size_; ++r)
            parts[size_t(r)].assign(all.begin() + offsets[size_t(r)],
                                    all.begin() + offsets[size_t(r)] + sizes[size_t(r)]);
        return parts;
    }
    void broadcast(std::vector<uint8_t>& bytes, int root) override {
        uint64_t n = bytes.size();
        ++collectives_;
        check(MPI_Bcast(&n, 1, MPI_UINT64_T, root, MPI_COMM_WORLD), "broadcast");
        bytes.resize(size_t(n));
        check(MPI_Bcast(bytes.data(), count(size_t(n), "broadcast"), MPI_BYTE, root, MPI_COMM_WORLD), "broadcast");
        if (rank_ == root) sent_ += (sizeof n + n) * uint64_t(size_ - 1);
    }
    void barrier() override {
        ++collectives_;
        check(MPI_Barrier(MPI_COMM_WORLD), "barrier");
    }
    uint64_t bytesSent() const override { return sent_; }
    uint64_t collectives() const override { return collectives_; }

private:
    template <class T>
    void sumInRankOrder(std::span<T> v) {
        const int n = count(v.size(), "sum");
        ++collectives_;
        std::vector<T> all(rank_ == 0 ? v.size() * size_t(size_) : 0);
        check(MPI_Gather(v.data(), n, datatype<T>(), all.data(), n, datatype<T>(), 0, MPI_COMM_WORLD), "gather");
        if (rank_ == 0) {
            for (size_t i = 0; i < v.size(); ++i) {
                T s = all[i];
                for (int r = 1; r < size_; ++r) s += all[size_t(r) * v.size() + i];
                v[i] = s;
            }
        } else {
            sent_ += v.size_bytes();
        }
        check(MPI_Bcast(v.data(), n, datatype<T>(), 0, MPI_COMM_WORLD), "broadcast");
        if (rank_ == 0) sent_ += v.size_bytes() * uint64_t(size_ - 1);
    }

    int rank_ = 0, size_ = 1;
    uint64_t sent_ = 0, collectives_ = 0;  // an operation of several MPI calls counts once
};

}  // namespace

MpiRuntime::MpiRuntime(int& argc, char**& argv) {
    int provided = 0;
    check(MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided), "init");
    // Errors come back as codes (check() turns them into caustica::Error) instead of aborting.
    MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
    world_ = std::make_unique<MpiWorld>();
}

MpiRuntime::~MpiRuntime() {
    world_.reset();
    MPI_Finalize();
}

void MpiRuntime::abortAll(int code) {
    MPI_Abort(MPI_COMM_WORLD, code);
    std::_Exit(code);  // MPI_Abort does not return; this only satisfies [[noreturn]]
}

}  // namespace caustica
