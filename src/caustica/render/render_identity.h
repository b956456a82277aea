// render_identity.h — the settings that make a render's image what it is, as named, readable
// entries: the contents of every input file, the -D values, resolution and crop, integrator and
// its parameters, seed. A checkpoint carries them; a resume with any of them different is refused
// with the first that differs. Device, ray tracer and execution mode are left out: they do not
// change the image (beyond rounding), so a render may resume on another device.
#pragma once

#include <string>
#include <vector>

#include "caustica/scene/stereo_rig.h"

namespace caustica {

struct IdentityEntry {
    std::string name;      // "scene file", "resolution", "mlt chains", ...
    std::string value;     // what a user reads: "scenes/a.xml, sha 3f2c0a1b9e8d7c6f"
    std::string identity;  // what must be equal: the content hash for a file, else the value
    bool operator==(const IdentityEntry&) const = default;
};

using RenderIdentity = std::vector<IdentityEntry>;

/// An entry whose identity is its value.
IdentityEntry identityEntry(std::string name, std::string value);
/// An entry for an input file: value "PATH, sha HASH", identity the 64-bit FNV-1a hash of the
/// file's bytes in hex (throws caustica::Error naming the file when it cannot be read).
IdentityEntry fileIdentityEntry(std::string name, const std::string& path);
/// A float as the shortest text that reads back to the same value ("0.1", not "1.00000001e-1").
std::string identityNumber(double value);
/// The same for a float: the shortest text that reads back to the same float ("0.1").
std::string identityNumber(float value);
/// The stereo rig's entry: "off", or its mode, interocular and convergence distances (so a mono
/// checkpoint never resumes a stereo render, nor the reverse).
IdentityEntry stereoIdentityEntry(const StereoSettings& stereo);

/// A render spread over `ranks` > 1 ranks (MPI) names their number: its checkpoint resumes only
/// with as many ranks. A single process adds no entry, so earlier checkpoints still resume.
IdentityEntry ranksIdentityEntry(int ranks);
/// "" when the checkpoint identity `saved` was written by `ranks` ranks (no entry: 1), else the one
/// line that refuses the resume, naming both counts.
std::string rankCountMismatch(const RenderIdentity& saved, int ranks);

/// The first entry of `saved` and `current` that differs, as "NAME differs (written for VALUE;
/// now VALUE)" ("... (not in this render)" / "(not in the checkpoint)" when one list is longer);
/// empty when they agree.
std::string firstIdentityDifference(const RenderIdentity& saved, const RenderIdentity& current);

}  // namespace caustica
