// progress.h — progress reporting for long renders: a bar with ETA on a terminal, plain periodic
// lines otherwise (logs, CI). Thread-safe to call from the render driver between passes.
#pragma once

#include <chrono>
#include <cstdio>
#include <string>

namespace caustica {

class ProgressReporter {
public:
    /// `total` work units (e.g. samples per pixel); `timeLimit` > 0 seconds also bounds the work,
    /// so the ETA is the earlier of the two. `out` is usually stderr.
    ProgressReporter(std::string label, double total, double timeLimitSeconds, std::FILE* out = stderr);
    ~ProgressReporter();

    /// Reports that `done` units are complete (monotonic).
    void update(double done);
    /// Ends the bar (prints the final state and a newline).
    void finish();
    double elapsedSeconds() const;

    /// Formats seconds as "1h02m03s", "2m03s" or "3.4s".
    static std::string formatDuration(double seconds);

private:
    void print(bool final);

    std::string label_;
    double total_, timeLimit_, done_ = 0;
    std::FILE* out_;
    bool interactive_;
    bool finished_ = false;
    std::chrono::steady_clock::time_point start_, lastPrint_;
};

}  // namespace caustica
