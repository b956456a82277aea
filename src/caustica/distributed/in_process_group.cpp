#include "caustica/distributed/in_process_group.h"

#include <algorithm>
#include <cstring>
#include <exception>
#include <thread>

#include "caustica/util/error.h"

namespace caustica {

/// A collective is two barriers: every rank writes its slot, waits, reads all slots (in rank
/// order), waits again so that no slot is overwritten while another rank still reads it.
struct InProcessGroup::State {
    explicit State(int n) : slots(n) {}
    std::mutex mutex;
    std::condition_variable changed;
    int arrived = 0;
    uint64_t generation = 0;
    bool broken = false;  // a rank threw: every wait throws from now on
    std::vector<std::vector<uint8_t>> slots;

    void wait() {
        std::unique_lock lock(mutex);
        if (broken) throw Error("another rank of the in-process group failed");
        const uint64_t gen = generation;
        if (++arrived == int(slots.size())) {
            arrived = 0;
            ++generation;
            changed.notify_all();
            return;
        }
        changed.wait(lock, [&] { return generation != gen || broken; });
        if (broken) throw Error("another rank of the in-process group failed");
    }
    void breakAll() {
        std::lock_guard lock(mutex);
        broken = true;
        changed.notify_all();
    }
};

namespace {

class InProcessRank final : public Communicator {
public:
    InProcessRank(InProcessGroup::State& state, int rank) : state_(state), rank_(rank) {}
    int rank() const override { return rank_; }
    int size() const override { return int(state_.slots.size()); }
    void sum(std::span<double> v) override { sumOf(v); }
    void sum(std::span<float> v) override { sumOf(v); }
    void sum(std::span<uint64_t> v) override { sumOf(v); }
    double max(double value) override {
        double m = value;
        exchange(asBytes(std::span(&value, 1)), [&] {
            for (const auto& s : state_.slots) m = std::max(m, fromBytes<double>(s)[0]);
        });
        return m;
    }
    std::vector<std::vector<uint8_t>> allGather(std::span<const uint8_t> bytes) override {
        std::vector<std::vector<uint8_t>> all;
        exchange(bytes, [&] { all = state_.slots; });
        return all;
    }
    void broadcast(std::vector<uint8_t>& bytes, int root) override {
        const bool mine = rank_ == root;
        exchange(mine ? std::span<const uint8_t>(bytes) : std::span<const uint8_t>(), [&] {
            if (!mine) bytes = state_.slots[root];
        });
    }
    void barrier() override { exchange({}, [] {}); }
    uint64_t bytesSent() const override { return sent_; }
    uint64_t collectives() const override { return collectives_; }

private:
    template <class T>
    static std::span<const uint8_t> asBytes(std::span<T> v) {
        return {reinterpret_cast<const uint8_t*>(v.data()), v.size_bytes()};
    }
    template <class T>
    static std::vector<T> fromBytes(const std::vector<uint8_t>& b) {
        std::vector<T> v(b.size() / sizeof(T));
        std::memcpy(v.data(), b.data(), v.size() * sizeof(T));
        return v;
    }
    template <class T>
    void sumOf(std::span<T> v) {
        exchange(asBytes(v), [&] {
            std::fill(v.begin(), v.end(), T(0));
            for (const auto& s : state_.slots) {  // rank order: the same bits on every rank
                const std::vector<T> part = fromBytes<T>(s);
                if (part.size() != v.size()) throw Error("ranks disagree on the size of a sum");
                for (size_t i = 0; i < v.size(); ++i) v[i] += part[i];
            }
        });
    }
    template <class Read>
    void exchange(std::span<const uint8_t> mine, Read&& read) {
        state_.slots[rank_].assign(mine.begin(), mine.end());
        sent_ += mine.size();
        ++collectives_;
        state_.wait();
        read();
        state_.wait();
    }

    InProcessGroup::State& state_;
    int rank_;
    uint64_t sent_ = 0, collectives_ = 0;
};

}  // namespace

InProcessGroup::InProcessGroup(int size) : state_(std::make_unique<State>(std::max(size, 1))) {
    for (int r = 0; r < std::max(size, 1); ++r) ranks_.push_back(std::make_unique<InProcessRank>(*state_, r));
}

InProcessGroup::~InProcessGroup() = default;

void InProcessGroup::run(const std::function<void(Communicator&)>& body) {
    std::vector<std::exception_ptr> errors(ranks_.size());
    std::vector<std::thread> threads;
    for (size_t r = 0; r < ranks_.size(); ++r)
        threads.emplace_back([&, r] {
            try {
                body(*ranks_[r]);
            } catch (...) {
                errors[r] = std::current_exception();
                state_->breakAll();
            }
        });
    for (std::thread& t : threads) t.join();
    // The first rank that failed on its own, not one woken by another's failure.
    std::exception_ptr first;
    for (const std::exception_ptr& e : errors) {
        if (!e) continue;
        try {
            std::rethrow_exception(e);
        } catch (const Error& err) {
            if (std::string(err.what()) == "another rank of the in-process group failed") {
                if (!first) first = e;
                continue;
            }
            std::rethrow_exception(e);
        } catch (...) {
            std::rethrow_exception(e);
        }
    }
    if (first) std::rethrow_exception(first);
}

}  // namespace caustica
