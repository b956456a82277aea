// kernel_stats.cpp — the kernel timing registry.
#include "caustica/parallel/kernel_stats.h"

#include <algorithm>

#include <fmt/format.h>

namespace caustica {

KernelStats& KernelStats::global() {
    static KernelStats stats;
    return stats;
}

void KernelStats::record(std::string_view name, double ms) {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = stats_.find(name);
    if (it == stats_.end())
        it = stats_.emplace(std::string(name), KernelStat{std::string(name)}).first;
    it->second.launches += 1;
    it->second.totalMs += ms;
}

std::vector<KernelStat> KernelStats::snapshot() const {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<KernelStat> out;
    out.reserve(stats_.size());
    for (const auto& [name, stat] : stats_) out.push_back(stat);
    return out;
}

void KernelStats::reset() {
    std::lock_guard<std::mutex> lock(mutex_);
    stats_.clear();
}

std::string KernelStats::table() const {
    std::vector<KernelStat> rows = snapshot();
    std::stable_sort(rows.begin(), rows.end(), [](const KernelStat& a, const KernelStat& b) {
        return a.totalMs > b.totalMs;
    });
    size_t width = 6;
    for (const KernelStat& r : rows) width = std::max(width, r.name.size());
    std::string s = fmt::format("{:<{}}  {:>10}  {:>12}  {:>10}\n", "kernel", width, "launches",
                                "total ms", "mean ms");
    for (const KernelStat& r : rows) {
        const double mean = r.launches ? r.totalMs / double(r.launches) : 0.0;
        s += fmt::format("{:<{}}  {:>10}  {:>12.3f}  {:>10.4f}\n", r.name, width, r.launches,
                         r.totalMs, mean);
    }
    return s;
}

}  // namespace caustica
