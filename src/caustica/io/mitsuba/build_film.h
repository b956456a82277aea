// build_film.h — the film (with its reconstruction filter) and the sampler nested in a sensor
// (build_film.cpp), used by the sensor builders (build_sensor.cpp).
#pragma once

#include "caustica/io/mitsuba/build_context.h"

namespace caustica::mitsuba {

/// The film entity `object` (hdrfilm or ldrfilm): the rendered image's size (a crop window's
/// when cropped) and filter in the returned FilmDesc; the full size and the crop offset in
/// `camera` (width, height, cropX, cropY).
FilmDesc buildFilm(BuildContext& ctx, int object, Camera& camera);

/// The sampler entity `object`: Scene::sampleCount (rounded as Mitsuba rounds it for the
/// sampler type) and Scene::seed.
void buildSampler(BuildContext& ctx, int object);

}  // namespace caustica::mitsuba
