// rank_sessions.h — an integrator's session on N ranks (InProcessGroup: ranks as threads), built
// as the Renderer builds it (registry entry, SessionContext with the rank's Communicator), for the
// *_ranks_tests: they drive step / develop / save / load of every rank in lock step as an MPI run
// does, without the Renderer around it.
#pragma once

#include <functional>
#include <memory>
#include <sstream>
#include <string>

#include "caustica/accel/accel.h"
#include "caustica/distributed/in_process_group.h"
#include "caustica/render/integrator_registry.h"
#include "caustica/render/render_request.h"
#include "caustica/scene/scene.h"

namespace caustica::test {

/// A scene, its ray tracer (the own BVH: the same bits on every CPU) and a request (integrator,
/// seed, parameters) that every rank's session is made from.
struct RankRig {
    const Scene& scene;
    RenderRequest request;
    Accel accel;

    RankRig(const Scene& s, RenderRequest r) : scene(s), request(std::move(r)), accel(s, AccelKind::Bvh) {}

    /// Runs body(session, comm) on `ranks` ranks, each with its own session; ranks = 1 is one
    /// process (singleProcess(), no group).
    void run(int ranks, const std::function<void(IntegratorSession&, Communicator&)>& body) const {
        auto onRank = [&](Communicator& comm) {
            IntegratorParams params = integratorParams(scene.integrator, request.integrator, request.integratorParams);
            const SessionContext context{scene, accel, Device::cpu(), *request.seed, request, params, nullptr, comm};
            const std::unique_ptr<IntegratorSession> session = findIntegrator(request.integrator).make(context);
            body(*session, comm);
        };
        if (ranks == 1) return onRank(singleProcess());
        InProcessGroup group(ranks);
        group.run(onRank);
    }
};

/// What the Renderer does with a checkpoint over ranks (the contract of docs/MPI.md): save is
/// collective and only rank 0's stream is the file; load gives every rank the whole file.
inline std::string saveOnRanks(const IntegratorSession& session, Communicator& comm) {
    std::ostringstream out;
    session.save(out);
    return comm.isRoot() ? out.str() : std::string();
}
inline void loadOnRanks(IntegratorSession& session, const std::string& file) {
    std::istringstream in(file);
    session.load(in);
}

}  // namespace caustica::test
