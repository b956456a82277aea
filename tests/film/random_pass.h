// random_pass.h — a SamplePass of K samples per pixel at random positions inside their pixels,
// radiance in [0, 10): the film tests' input.
#pragma once

#include <random>

#include "caustica/film/film.h"

namespace caustica::test {

inline SamplePass randomPass(int w, int h, int k, uint32_t seed) {
    SamplePass pass(w, h, k);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int s = 0; s < k; ++s)
                pass.at(x, y, s) = {Vec2f(x + u(rng) * 0.999f, y + u(rng) * 0.999f),
                                    Spectrum(10 * u(rng), 10 * u(rng), 10 * u(rng))};
    return pass;
}

}  // namespace caustica::test
