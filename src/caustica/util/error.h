// error.h — errors that carry where they come from (file, line) and why.
#pragma once

#include <stdexcept>
#include <string>

namespace caustica {

/// Thrown by loaders (host code only). what() is "file:line: reason" (line omitted when 0), the
/// one line the command line prints before exiting non-zero.
class Error : public std::runtime_error {
public:
    Error(std::string file, int line, std::string reason)
        : std::runtime_error(format(file, line, reason)),
          file_(std::move(file)), line_(line), reason_(std::move(reason)) {}
    explicit Error(std::string reason) : Error("", 0, std::move(reason)) {}

    const std::string& file() const { return file_; }
    int line() const { return line_; }
    const std::string& reason() const { return reason_; }

private:
    static std::string format(const std::string& file, int line, const std::string& reason) {
        std::string s;
        if (!file.empty()) s += file + ":";
        if (line > 0) s += std::to_string(line) + ":";
        if (!s.empty()) s += " ";
        return s + reason;
    }
    std::string file_;
    int line_ = 0;
    std::string reason_;
};

}  // namespace caustica
