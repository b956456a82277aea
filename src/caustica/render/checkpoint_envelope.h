// checkpoint_envelope.h — the one checkpoint format of every integrator:
//
//   char[8] "CAUSTCKP" | u32 version | string integrator | u64 n | n x (name, value, identity)
//   | f64 render seconds so far | f64 samples (or mutations) per pixel so far
//   | u64 FNV-1a hash of the header above | the integrator's payload (its own format and checks)
//
// Strings are u64 length + bytes, numbers little-endian (util/binary_io.h). The header is read
// and verified whole before a payload is touched, so a checkpoint of another render is refused
// without changing anything.
#pragma once

#include <iosfwd>
#include <string>

#include "caustica/render/render_identity.h"

namespace caustica {

struct CheckpointHeader {
    std::string integrator;
    RenderIdentity identity;
    double seconds = 0;         // rendering time of the whole render so far (every run)
    double samplesPerPixel = 0; // samples per pixel (mutations per pixel for mlt) so far
};

void writeCheckpointHeader(std::ostream& out, const CheckpointHeader& header);
/// Reads and verifies a header (magic, version, hash); throws caustica::Error (without the file
/// name: callers add it) for a file that is not a caustica checkpoint of this version or is
/// damaged.
CheckpointHeader readCheckpointHeader(std::istream& in);

/// The one line a refused resume prints, without the file name: "integrator differs (...)" or
/// the first setting that differs; empty when `saved` fits `current`.
std::string checkpointMismatch(const CheckpointHeader& saved, const std::string& integrator,
                               const RenderIdentity& identity);

}  // namespace caustica
