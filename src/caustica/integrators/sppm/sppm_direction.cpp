#include "caustica/integrators/sppm/sppm_direction.h"

#include <cstdio>

namespace caustica {

std::string SppmDirectionChooser::describe() const {
    if (setting_ != PhotonDirection::Auto) return photonDirectionName(setting_);
    char line[200];
    switch (stage_) {
        case Stage::Pilot: return "auto (no photon pass yet)";
        case Stage::TryGather:
        case Stage::TryDeposit:
            std::snprintf(line, sizeof line, "auto (%.3g photons stored per visible point; timing both directions)",
                          perVisiblePoint_);
            return line;
        case Stage::Decided: break;
    }
    if (depositSeconds_ > 0 || gatherSeconds_ > 0)
        std::snprintf(line, sizeof line,
                      "%s (auto: %.3g photons stored per visible point; passes timed: gather %.3g s, deposit %.3g s)",
                      photonDirectionName(chosen_), perVisiblePoint_, gatherSeconds_, depositSeconds_);
    else
        std::snprintf(line, sizeof line, "%s (auto: %.3g photons stored per visible point, >= %.3g)",
                      photonDirectionName(chosen_), perVisiblePoint_, kSppmGatherWithoutTrial);
    return line;
}

}  // namespace caustica
