// stereo_rig.h — turns a scene's camera into a stereo rig (camera.h: two eyes side by side on one
// film twice as wide), derived once on the host. Modes, as Blender Cycles and Maya:
//   off-axis  eyes parallel, each frustum shifted (asymmetric) so that zero parallax lies at the
//             convergence distance;
//   parallel  eyes parallel, no shift (zero parallax at infinity);
//   toe-in    each eye rotated about its vertical axis to look at the point on the camera's axis
//             at the convergence distance (symmetric frusta; gives vertical parallax off-axis).
// The eyes sit at ± interocular / 2 along the camera's horizontal axis, the left eye on the
// viewer's left (Mitsuba's camera +x points left, so the left eye is at camera x = +interocular/2).
// Distances are in world units. Orthographic sensors are refused: stereo needs a centre of
// projection. docs/STEREO.md.
#pragma once

#include <cstdint>
#include <string>

#include "caustica/scene/scene.h"

namespace caustica {

enum class StereoMode : uint32_t { Off, OffAxis, Parallel, ToeIn };

struct StereoSettings {
    StereoMode mode = StereoMode::Off;
    Float interocular = 0.065f;  // metres (world units) between the eyes; Cycles' default
    Float convergence = 1.95f;   // distance of zero parallax (off-axis) or of the toe-in point
};

/// "off-axis" | "parallel" | "toe-in" | "off"; anything else throws caustica::Error.
StereoMode parseStereoMode(const std::string& name);
const char* stereoModeName(StereoMode mode);

/// The seed of eye `eye`'s camera streams: the left eye keeps the render's seed, the right eye
/// gets its own (so the eyes' noise is independent), and a mono render of the right eye's camera
/// (eyeCamera) at stereoEyeSeed(seed, 1) draws exactly the right eye's samples.
CA_HD_INLINE uint64_t stereoEyeSeed(uint64_t seed, int eye) {
    return eye == 0 ? seed : seed ^ 0x52494748545f4559ull;  // "RIGHT_EY"
}

/// Refuses (caustica::Error, one line naming the option) mode Off and a non-positive or
/// non-finite interocular or convergence distance.
void checkStereoSettings(const StereoSettings& settings);

/// Makes `camera` (film width `filmWidth` pixels, crop included) a stereo rig: eyeWidth =
/// filmWidth, both eyes' transforms and shifts. Returns the rendered film's new width
/// (2 filmWidth). Throws caustica::Error for an orthographic camera, a non-positive or non-finite
/// interocular or convergence distance, or mode Off.
int makeStereoRig(Camera& camera, int filmWidth, const StereoSettings& settings);

/// The scene's camera made a rig and its film widened (makeStereoRig); nothing for mode Off.
void applyStereo(Scene& scene, const StereoSettings& settings);

/// The ordinary (mono) camera of one eye of a rig: renders exactly that eye's half of the film.
Camera eyeCamera(const Camera& rig, int eye);

}  // namespace caustica
