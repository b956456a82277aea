// scene_test_util.h — helpers for the io tests: temporary directories, files written and read
// back byte for byte, loading XML strings, and checking that an error names the right file, line
// and reason.
#pragma once

#include <gtest/gtest.h>

#include <unistd.h>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>

#include "caustica/io/scene_loader.h"
#include "caustica/util/error.h"

namespace caustica::test {

/// Writes `bytes` to the file at `path` (binary-exact).
inline void writeBytes(const std::string& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary) << bytes;
}

/// The bytes of the file at `path` (binary-exact; empty when it cannot be read).
inline std::string readBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

/// A fresh directory under the system temp dir, removed when the object dies.
/// The text of the scene's <integrator> parameter `name` as io/ keeps it ("" when not given).
inline std::string integratorParam(const Scene& scene, const std::string& name) {
    for (const IntegratorParam& p : scene.integrator.params)
        if (p.name == name) return p.text;
    return {};
}

class TempDir {
public:
    TempDir() {
        static std::atomic<int> counter{0};
        path_ = std::filesystem::temp_directory_path() /
                ("caustica_io_test_" + std::to_string(getpid()) + "_" + std::to_string(counter++));
        std::filesystem::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    std::string path(const std::string& name) const { return (path_ / name).string(); }
    /// Writes `content` to `name` (binary-exact) and returns the full path.
    std::string write(const std::string& name, const std::string& content) const {
        std::filesystem::path p = path_ / name;
        std::filesystem::create_directories(p.parent_path());
        // Removing first is much faster than truncating on ext4 (no flush of the old data).
        std::filesystem::remove(p);
        writeBytes(p.string(), content);
        return p.string();
    }

private:
    std::filesystem::path path_;
};

/// The minimal sensor every loadable scene needs.
inline const char* kSensor =
    R"(<sensor type="perspective"><float name="fov" value="45"/></sensor>)";

/// `<scene version="3.0.0">` + body + `</scene>`, with the default sensor unless told otherwise.
inline std::string sceneXml(const std::string& body, bool withSensor = true) {
    return std::string("<scene version=\"3.0.0\">\n") + (withSensor ? kSensor : "") + "\n" + body +
           "\n</scene>\n";
}

/// Writes `xml` to a temp file and loads it.
inline Scene loadXml(const TempDir& dir, const std::string& xml,
                     std::vector<std::string>* warnings = nullptr,
                     const std::map<std::string, std::string>& defines = {}) {
    std::vector<std::string> local;
    return loadScene(dir.write("scene.xml", xml), defines, warnings ? warnings : &local);
}

/// Runs `fn`, expecting a caustica::Error whose message contains `file`, ":line:" and `reason`.
inline void expectError(const std::function<void()>& fn, const std::string& file, int line,
                        const std::string& reason) {
    try {
        fn();
        ADD_FAILURE() << "no error thrown; expected: " << reason;
    } catch (const Error& e) {
        std::string msg = e.what();
        EXPECT_NE(msg.find(file), std::string::npos) << "file '" << file << "' not in: " << msg;
        if (line > 0) {
            std::string tag = std::string(1, ':').append(std::to_string(line)).append(1, ':');
            EXPECT_NE(msg.find(tag), std::string::npos) << "line " << line << " not in: " << msg;
        }
        EXPECT_NE(msg.find(reason), std::string::npos)
            << "reason '" << reason << "' not in: " << msg;
        EXPECT_EQ(msg.find('\n'), std::string::npos) << "message spans lines: " << msg;
    }
}

/// True if some warning contains all of the given pieces.
inline bool hasWarning(const std::vector<std::string>& warnings,
                       std::initializer_list<std::string> pieces) {
    for (const std::string& w : warnings) {
        bool all = true;
        for (const std::string& p : pieces) all &= w.find(p) != std::string::npos;
        if (all) return true;
    }
    return false;
}

}  // namespace caustica::test
