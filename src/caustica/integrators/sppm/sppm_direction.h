// sppm_direction.h — direction "auto" of the photon mappers: which of the photon pass's two
// directions (sppm_driver.h) a driver runs. Both give the same photon sums to the bit (64-bit
// fixed point), so the choice changes the time of an iteration, never the image.
//
// Which is faster depends on the scene more than on any one count (docs/SPPM.md, "Direction"):
// gather stores, sorts and indexes every photon and then queries once per visible point;
// deposit indexes the visible points and then adds every photon into each sphere covering it
// with atomics. With many photons stored per visible point, gather won every measurement
// (1.1-2.5x); with few, either may win (deposit by 2.3x on glass-caustic at 1920x1080, gather
// by 1.1-1.3x on cornell-water at 512x512 and 1024x1024). So: the first pass's pilot (1/64 of the
// photon paths, counted, not stored) estimates the photons a pass stores; with at least
// kSppmGatherWithoutTrial of them per visible point the driver gathers, with fewer it runs
// passes in both directions, alternating, and keeps the one whose second pass was the faster
// (photon pass, structure and gather, the pilot left out). A direction's first pass is not
// compared: it pays for first-touch page faults of buffers of sizes not allocated before,
// which made deposit's first pass on glass-caustic 1.4x its later ones.
#pragma once

#include <cstdint>
#include <string>

#include "caustica/integrators/sppm/sppm_settings.h"

namespace caustica {

/// Photons stored per visible point from which direction "auto" gathers without timing deposit.
/// Deposit lost at every ratio measured from 0.16 up (2026-11-29: cornell-water and
/// glass-caustic, 128x128 to 1024x1024, 2^11 to 2^22 photon paths per iteration).
inline constexpr double kSppmGatherWithoutTrial = 0.25;

class SppmDirectionChooser {
public:
    explicit SppmDirectionChooser(PhotonDirection setting = PhotonDirection::Gather) : setting_(setting) {
        if (setting != PhotonDirection::Auto) {
            stage_ = Stage::Decided;
            chosen_ = setting;
        }
    }

    /// Whether the next pass needs the pilot's estimate first (pilot()).
    bool needsPilot() const { return stage_ == Stage::Pilot; }
    /// The pilot's estimate: photons a pass stores, and the visible points it gathers at.
    void pilot(double storedPhotons, uint64_t visiblePoints) {
        if (stage_ != Stage::Pilot) return;
        perVisiblePoint_ = visiblePoints > 0 ? storedPhotons / double(visiblePoints) : 0;
        if (perVisiblePoint_ >= kSppmGatherWithoutTrial) {
            chosen_ = PhotonDirection::Gather;
            stage_ = Stage::Decided;
        } else {
            stage_ = Stage::TryGather;
        }
    }
    /// The direction of the next photon pass (never Auto).
    PhotonDirection next() const {
        switch (stage_) {
            case Stage::TryGather: return PhotonDirection::Gather;
            case Stage::TryDeposit: return PhotonDirection::Deposit;
            default: return chosen_;
        }
    }
    /// A pass in next()'s direction took `seconds` (photon pass, structure and gather).
    void passed(double seconds) {
        if (stage_ == Stage::TryGather) {
            gatherSeconds_ = seconds;
            stage_ = Stage::TryDeposit;
        } else if (stage_ == Stage::TryDeposit) {
            depositSeconds_ = seconds;
            if (++trialRounds_ < kTrialRounds) {
                stage_ = Stage::TryGather;
                return;
            }
            chosen_ = depositSeconds_ < gatherSeconds_ ? PhotonDirection::Deposit : PhotonDirection::Gather;
            stage_ = Stage::Decided;
        }
    }
    bool decided() const { return stage_ == Stage::Decided; }
    /// The direction passes take: the setting, or what auto chose (Auto until it has chosen).
    PhotonDirection current() const { return decided() ? chosen_ : PhotonDirection::Auto; }
    PhotonDirection setting() const { return setting_; }
    /// What was chosen and why, e.g. "deposit (auto: 0.081 photons stored per visible point;
    /// passes timed: gather 0.0531 s, deposit 0.0412 s)".
    std::string describe() const;

private:
    enum class Stage { Pilot, TryGather, TryDeposit, Decided };
    static constexpr int kTrialRounds = 2;  // gather, deposit, gather, deposit: the second of each compared
    PhotonDirection setting_;
    Stage stage_ = Stage::Pilot;
    PhotonDirection chosen_ = PhotonDirection::Gather;
    int trialRounds_ = 0;
    double perVisiblePoint_ = 0, gatherSeconds_ = 0, depositSeconds_ = 0;
};

}  // namespace caustica
