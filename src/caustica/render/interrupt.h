// interrupt.h — Ctrl-C (SIGINT) and SIGTERM during a render: the first asks the loop to finish
// the current step, write the images and a checkpoint; a second quits at once, and says that the
// last complete checkpoint (written atomically) is intact.
#pragma once

#include <atomic>
#include <string>

namespace caustica {

/// Installs the handlers for its lifetime (one at a time; the previous handlers come back).
class InterruptGuard {
public:
    /// `checkpoint`: named by the message of a second interrupt ("" when there is none).
    explicit InterruptGuard(const std::string& checkpoint);
    ~InterruptGuard();
    InterruptGuard(const InterruptGuard&) = delete;
    InterruptGuard& operator=(const InterruptGuard&) = delete;

    /// Set by the first interrupt.
    static const std::atomic<bool>& requested();
};

}  // namespace caustica
