// agreed_error.h — failures every rank knows about. Where ranks may diverge (a scene that loads on
// one host and not on another, a pass that runs out of memory on one rank), each rank runs the
// step under agreeOnFailure(): the ranks then exchange their errors (Communicator::firstError)
// and, when any failed, every rank throws the same AgreedError("rank R: MESSAGE"), so all of them
// end together with the failing rank's message and none waits for a rank that has given up.
#pragma once

#include <new>
#include <string>

#include "caustica/distributed/communicator.h"
#include "caustica/util/error.h"

namespace caustica {

/// An error every rank of the render has thrown (see the file comment).
class AgreedError : public Error {
public:
    using Error::Error;
};

/// One line for an exception caught in flight (std::bad_alloc reads "out of memory").
std::string failureMessage(const std::exception& e);

/// Runs `body` on every rank; when it throws on any, every rank throws AgreedError with the
/// message of the lowest failing rank. Collective (one small exchange) when comm.size() > 1; a
/// single process runs `body` alone and lets its exception through unchanged. `body` itself must
/// not call collectives (a rank that throws would leave the others waiting in them).
template <class Body>
void agreeOnFailure(Communicator& comm, Body&& body) {
    if (comm.size() == 1) {
        body();
        return;
    }
    std::string mine;
    try {
        body();
    } catch (const std::exception& e) {
        mine = failureMessage(e);
    }
    if (std::string first = comm.firstError(mine); !first.empty()) throw AgreedError(std::move(first));
}

}  // namespace caustica
