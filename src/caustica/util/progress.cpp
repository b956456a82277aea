#include "caustica/util/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>

namespace caustica {

ProgressReporter::ProgressReporter(std::string label, double total, double timeLimitSeconds, std::FILE* out)
    : label_(std::move(label)), total_(total), timeLimit_(timeLimitSeconds), out_(out),
      interactive_(out && isatty(fileno(out))), start_(std::chrono::steady_clock::now()),
      lastPrint_(start_) {}

ProgressReporter::~ProgressReporter() { finish(); }

double ProgressReporter::elapsedSeconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

std::string ProgressReporter::formatDuration(double s) {
    if (!std::isfinite(s) || s < 0) return "--";
    char buf[32];
    if (s < 60) {
        std::snprintf(buf, sizeof buf, "%.1fs", s);
    } else if (s < 3600) {
        std::snprintf(buf, sizeof buf, "%dm%02ds", int(s) / 60, int(s) % 60);
    } else {
        std::snprintf(buf, sizeof buf, "%dh%02dm%02ds", int(s) / 3600, (int(s) / 60) % 60, int(s) % 60);
    }
    return buf;
}

void ProgressReporter::update(double done) {
    done_ = done;
    auto now = std::chrono::steady_clock::now();
    double sinceLast = std::chrono::duration<double>(now - lastPrint_).count();
    // A terminal gets a live bar; logs get a line every 10 seconds.
    if (sinceLast >= (interactive_ ? 0.1 : 10.0)) {
        lastPrint_ = now;
        print(false);
    }
}

void ProgressReporter::finish() {
    if (finished_ || !out_) return;
    finished_ = true;
    print(true);
}

void ProgressReporter::print(bool final) {
    if (!out_) return;
    double elapsed = elapsedSeconds();
    double fraction = total_ > 0 ? std::min(1.0, done_ / total_) : 0;
    if (timeLimit_ > 0) fraction = std::max(fraction, std::min(1.0, elapsed / timeLimit_));
    double eta = fraction > 0 ? elapsed / fraction - elapsed : -1;
    if (final) eta = 0;
    char counts[64];
    if (total_ > 0 && std::isfinite(total_))
        std::snprintf(counts, sizeof counts, "%g/%g", done_, total_);
    else
        std::snprintf(counts, sizeof counts, "%g", done_);
    if (interactive_) {
        constexpr int kWidth = 30;
        int filled = int(fraction * kWidth + 0.5);
        std::string bar(size_t(filled), '#');
        bar.resize(kWidth, '.');
        std::fprintf(out_, "\r%s [%s] %3.0f%% %s  elapsed %s  ETA %s   ", label_.c_str(), bar.c_str(),
                     fraction * 100, counts, formatDuration(elapsed).c_str(), formatDuration(eta).c_str());
        if (final) std::fputc('\n', out_);
    } else {
        std::fprintf(out_, "%s: %3.0f%% %s  elapsed %s  ETA %s\n", label_.c_str(), fraction * 100, counts,
                     formatDuration(elapsed).c_str(), formatDuration(eta).c_str());
    }
    std::fflush(out_);
}

}  // namespace caustica
