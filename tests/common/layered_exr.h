// layered_exr.h — tests write EXRs with extra channels and a `caustica.aovs` attribute, as a
// render with AOVs does, without depending on the renderer's writer.
#pragma once

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>

#include <functional>
#include <string>
#include <vector>

namespace caustica::test {

/// Writes a width x height float EXR with channels R, G, B and `extra`, channel k (in that
/// order, R = 0) holding value(k, x, y), and the `caustica.aovs` attribute unless `aovs` is "".
inline void writeLayeredExr(const std::string& path, int width, int height, const std::vector<std::string>& extra,
                            const std::string& aovs, const std::function<float(int, int, int)>& value) {
    Imf::Header header(width, height);
    std::vector<std::string> all = {"R", "G", "B"};
    all.insert(all.end(), extra.begin(), extra.end());
    for (const std::string& c : all) header.channels().insert(c, Imf::Channel(Imf::FLOAT));
    if (!aovs.empty()) header.insert("caustica.aovs", Imf::StringAttribute(aovs));
    std::vector<std::vector<float>> data(all.size(), std::vector<float>(size_t(width) * size_t(height)));
    Imf::FrameBuffer fb;
    for (size_t k = 0; k < all.size(); ++k) {
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) data[k][size_t(y) * size_t(width) + size_t(x)] = value(int(k), x, y);
        fb.insert(all[k], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(data[k].data()), sizeof(float),
                                     sizeof(float) * size_t(width)));
    }
    Imf::OutputFile file(path.c_str(), header);
    file.setFrameBuffer(fb);
    file.writePixels(height);
}

}  // namespace caustica::test
