// kernel_stats.h — per-kernel launch counts and time, recorded by parallelFor when enabled.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

namespace caustica {

/// Launches and total milliseconds of one named kernel.
struct KernelStat {
    std::string name;
    uint64_t launches = 0;
    double totalMs = 0.0;
};

/// Process-wide registry of kernel timings, keyed by the launch name given to parallelFor (and by
/// the CUDA launcher in cuda/parallel_for_cuda.h). Disabled by default: a disabled registry costs
/// one relaxed atomic load per launch. CPU launches are timed with steady_clock around the whole
/// parallelFor; CUDA launches with a pair of CUDA events (which synchronizes after the launch).
/// Thread-safe.
class KernelStats {
public:
    static KernelStats& global();

    void setEnabled(bool on) { enabled_.store(on, std::memory_order_relaxed); }
    bool enabled() const { return enabled_.load(std::memory_order_relaxed); }

    /// Adds one launch of `name` that took `ms` milliseconds.
    void record(std::string_view name, double ms);
    /// All kernels recorded so far, sorted by name.
    std::vector<KernelStat> snapshot() const;
    void reset();
    /// A fixed-width table: kernel, launches, total ms, mean ms; sorted by total time, descending.
    std::string table() const;

private:
    std::atomic<bool> enabled_{false};
    mutable std::mutex mutex_;
    std::map<std::string, KernelStat, std::less<>> stats_;
};

/// Times a scope on the host and records it under `name` when the global registry is enabled.
class KernelTimer {
public:
    explicit KernelTimer(const char* name)
        : name_(KernelStats::global().enabled() ? name : nullptr) {
        if (name_) start_ = std::chrono::steady_clock::now();
    }
    ~KernelTimer() {
        if (!name_) return;
        const auto end = std::chrono::steady_clock::now();
        KernelStats::global().record(
            name_, std::chrono::duration<double, std::milli>(end - start_).count());
    }
    KernelTimer(const KernelTimer&) = delete;
    KernelTimer& operator=(const KernelTimer&) = delete;

private:
    const char* name_;
    std::chrono::steady_clock::time_point start_{};
};

}  // namespace caustica
