#include "caustica/integrators/mlt/mlt_rank_checkpoint.h"

namespace caustica {
namespace {

/// Part q's array `member` for every q, concatenated; a placeholder (width 0) taken from part 0.
template <class T>
std::vector<T> concatenated(const std::vector<MltCheckpoint>& parts, std::vector<T> MltCheckpoint::*member,
                            size_t width) {
    if (width == 0) return parts[0].*member;
    std::vector<T> out;
    for (const MltCheckpoint& p : parts) out.insert(out.end(), (p.*member).begin(), (p.*member).end());
    return out;
}

/// Elements [first * width, (first + count) * width) of `v`; a placeholder (width 0) as it is.
template <class T>
std::vector<T> slice(const std::vector<T>& v, uint64_t first, uint64_t count, size_t width) {
    if (width == 0) return v;
    return std::vector<T>(v.begin() + std::ptrdiff_t(first * width), v.begin() + std::ptrdiff_t((first + count) * width));
}

}  // namespace

MltCheckpoint mergeMltCheckpoints(const std::vector<MltCheckpoint>& parts, const MltChainWidths& widths) {
    MltCheckpoint whole;
    whole.stats = parts[0].stats;
    whole.stats.rays = 0;
    for (const MltCheckpoint& p : parts) whole.stats.rays += p.stats.rays;
    whole.b = parts[0].b;
    whole.pixelWeight = parts[0].pixelWeight;
    whole.fine = concatenated(parts, &MltCheckpoint::fine, widths.fine);
    whole.coarse = concatenated(parts, &MltCheckpoint::coarse, widths.coarse);
    whole.values = concatenated(parts, &MltCheckpoint::values, widths.values);
    whole.pos = concatenated(parts, &MltCheckpoint::pos, 1);
    whole.value = concatenated(parts, &MltCheckpoint::value, 1);
    whole.importance = concatenated(parts, &MltCheckpoint::importance, 1);
    whole.usedDims = concatenated(parts, &MltCheckpoint::usedDims, 1);
    whole.image = concatenated(parts, &MltCheckpoint::image, 1);
    // Slot t of the unfinished batch holds every chain's splats of one iteration.
    const size_t slots = parts[0].pendingSplats.size() / (parts[0].pos.size() * widths.splats);
    for (size_t t = 0; t < slots; ++t)
        for (const MltCheckpoint& p : parts) {
            const size_t n = p.pos.size() * widths.splats;
            whole.pendingSplats.insert(whole.pendingSplats.end(), p.pendingSplats.begin() + std::ptrdiff_t(t * n),
                                       p.pendingSplats.begin() + std::ptrdiff_t((t + 1) * n));
        }
    return whole;
}

MltCheckpoint mltCheckpointPart(const MltCheckpoint& whole, const MltChainWidths& widths, MltShare share,
                                uint32_t totalChains, int rank, int ranks) {
    MltCheckpoint part;
    part.stats = whole.stats;
    part.b = whole.b;
    part.pixelWeight = whole.pixelWeight;
    part.fine = slice(whole.fine, share.first, share.count, widths.fine);
    part.coarse = slice(whole.coarse, share.first, share.count, widths.coarse);
    part.values = slice(whole.values, share.first, share.count, widths.values);
    part.pos = slice(whole.pos, share.first, share.count, 1);
    part.value = slice(whole.value, share.first, share.count, 1);
    part.importance = slice(whole.importance, share.first, share.count, 1);
    part.usedDims = slice(whole.usedDims, share.first, share.count, 1);
    part.image = slice(whole.image, uint64_t(rank), 1, whole.image.size() / size_t(ranks));
    const size_t slotSplats = size_t(totalChains) * widths.splats;
    for (size_t t = 0; t < whole.pendingSplats.size() / slotSplats; ++t) {
        const auto slot = whole.pendingSplats.begin() + std::ptrdiff_t(t * slotSplats);
        part.pendingSplats.insert(part.pendingSplats.end(), slot + std::ptrdiff_t(share.first * widths.splats),
                                  slot + std::ptrdiff_t((share.first + share.count) * widths.splats));
    }
    return part;
}

}  // namespace caustica
