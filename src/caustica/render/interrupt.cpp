#include "caustica/render/interrupt.h"

#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstring>

namespace caustica {
namespace {

std::atomic<bool> gRequested{false};
std::atomic<int> gCount{0};
char gSecondMessage[1024];  // composed before the handlers are installed: write() is signal-safe
size_t gSecondLength = 0;
void (*gPreviousInt)(int) = SIG_DFL;
void (*gPreviousTerm)(int) = SIG_DFL;

void onSignal(int) {
    if (gCount.fetch_add(1) == 0) {
        gRequested.store(true);
        static const char first[] =
            "\ninterrupted: finishing the current step, then writing the images and the checkpoint "
            "(interrupt again to quit at once)\n";
        (void)!::write(STDERR_FILENO, first, sizeof first - 1);
        return;
    }
    (void)!::write(STDERR_FILENO, gSecondMessage, gSecondLength);
    ::_exit(130);
}

}  // namespace

InterruptGuard::InterruptGuard(const std::string& checkpoint) {
    gRequested.store(false);
    gCount.store(0);
    const std::string message =
        checkpoint.empty() ? "\ninterrupted again: quitting now, nothing saved\n"
                           : "\ninterrupted again: quitting now; the last complete checkpoint " + checkpoint +
                                 " is intact (continue with --resume)\n";
    gSecondLength = std::min(message.size(), sizeof gSecondMessage);
    std::memcpy(gSecondMessage, message.data(), gSecondLength);
    gPreviousInt = std::signal(SIGINT, onSignal);
    gPreviousTerm = std::signal(SIGTERM, onSignal);
}

InterruptGuard::~InterruptGuard() {
    std::signal(SIGINT, gPreviousInt);
    std::signal(SIGTERM, gPreviousTerm);
}

const std::atomic<bool>& InterruptGuard::requested() { return gRequested; }

}  // namespace caustica
