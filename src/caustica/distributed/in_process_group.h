// in_process_group.h — N ranks as N threads of one process, sharing memory instead of MPI: the
// tests (and anyone without MPI) run a distributed render's exact code path with it.
//
//     InProcessGroup group(2);
//     group.run([&](Communicator& comm) { Renderer r(scene, request, nullptr, comm); ... });
#pragma once

#include <condition_variable>
#include <functional>
#include <memory>
#include <mutex>
#include <vector>

#include "caustica/distributed/communicator.h"

namespace caustica {

class InProcessGroup {
public:
    explicit InProcessGroup(int size);
    ~InProcessGroup();
    InProcessGroup(const InProcessGroup&) = delete;
    InProcessGroup& operator=(const InProcessGroup&) = delete;

    int size() const { return int(ranks_.size()); }
    Communicator& rank(int r) { return *ranks_[r]; }

    /// Runs `body` on size() threads, one per rank, and waits for all. When a rank throws, the
    /// others are woken from any collective with an exception too (nothing hangs), and run()
    /// rethrows the lowest failing rank's exception.
    void run(const std::function<void(Communicator&)>& body);

    /// Shared by the ranks (in_process_group.cpp): the slots of the collective in flight.
    struct State;

private:
    std::unique_ptr<State> state_;
    std::vector<std::unique_ptr<Communicator>> ranks_;
};

}  // namespace caustica
