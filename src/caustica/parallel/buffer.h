// buffer.h — a typed array in the memory of one Device.
#pragma once

#include <cstddef>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "caustica/parallel/backend.h"
#include "caustica/parallel/device.h"
#include "caustica/util/error.h"
#include "caustica/util/span.h"

namespace caustica {

/// `count` elements of T on a Device: a 64-byte aligned host allocation on the CPU, plain
/// cudaMalloc memory on CUDA (never managed memory, so the host must not dereference it).
/// Contents start uninitialized (zero() clears them). Move-only; copies between host and device
/// are explicit (copyFromHost / copyToHost) and synchronous. span() is valid on the buffer's
/// device only, until the buffer is destroyed or moved from. T must be trivially copyable.
template <class T>
class Buffer {
    static_assert(std::is_trivially_copyable_v<T>,
                  "Buffer<T> holds raw bytes: T must be trivially copyable");

public:
    Buffer() = default;
    Buffer(const Device& device, size_t count)
        : device_(device),
          ptr_(static_cast<T*>(detail::allocateOn(device, count * sizeof(T)))),
          count_(count) {}
    /// Allocates host.size() elements and uploads them.
    Buffer(const Device& device, Span<const T> host) : Buffer(device, host.size()) {
        copyFromHost(host);
    }
    Buffer(const Device& device, const std::vector<T>& host)
        : Buffer(device, Span<const T>(host.data(), host.size())) {}
    ~Buffer() { detail::releaseOn(device_, ptr_); }

    Buffer(Buffer&& o) noexcept
        : device_(o.device_),
          ptr_(std::exchange(o.ptr_, nullptr)),
          count_(std::exchange(o.count_, 0)) {}
    Buffer& operator=(Buffer&& o) noexcept {
        if (this != &o) {
            detail::releaseOn(device_, ptr_);
            device_ = o.device_;
            ptr_ = std::exchange(o.ptr_, nullptr);
            count_ = std::exchange(o.count_, 0);
        }
        return *this;
    }
    Buffer(const Buffer&) = delete;
    Buffer& operator=(const Buffer&) = delete;

    size_t size() const { return count_; }
    bool empty() const { return count_ == 0; }
    const Device& device() const { return device_; }
    /// The device pointer (host pointer on the CPU).
    T* data() const { return ptr_; }
    Span<T> span() const { return Span<T>(ptr_, count_); }
    Span<const T> constSpan() const { return Span<const T>(ptr_, count_); }

    /// Copies host[0, host.size()) to elements [offset, offset + host.size()).
    void copyFromHost(Span<const T> host, size_t offset = 0) {
        checkRange(offset, host.size(), "copyFromHost");
        detail::copyOn(device_, ptr_ + offset, host.data(), host.size() * sizeof(T));
    }
    void copyFromHost(const std::vector<T>& host, size_t offset = 0) {
        copyFromHost(Span<const T>(host.data(), host.size()), offset);
    }
    /// Copies elements [offset, offset + host.size()) to host.
    void copyToHost(Span<T> host, size_t offset = 0) const {
        checkRange(offset, host.size(), "copyToHost");
        detail::copyOn(device_, host.data(), ptr_ + offset, host.size() * sizeof(T));
    }
    /// All elements, downloaded.
    std::vector<T> toHost() const {
        std::vector<T> out(count_);
        copyToHost(Span<T>(out.data(), out.size()));
        return out;
    }
    /// Sets every byte to zero.
    void zero() { detail::zeroOn(device_, ptr_, count_ * sizeof(T)); }

private:
    void checkRange(size_t offset, size_t n, const char* what) const {
        if (offset > count_ || n > count_ - offset) {
            throw Error(std::string("Buffer::") + what + ": range [" + std::to_string(offset) +
                        ", " + std::to_string(offset + n) + ") outside a buffer of " +
                        std::to_string(count_));
        }
    }

    Device device_{};
    T* ptr_ = nullptr;
    size_t count_ = 0;
};

}  // namespace caustica
