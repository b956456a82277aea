// span.h — a pointer and a length: how kernels see flat scene buffers on either device.
#pragma once

#include <cstddef>
#include <vector>

#include "caustica/util/platform.h"

namespace caustica {

template <class T>
struct Span {
    T* ptr = nullptr;
    size_t count = 0;

    constexpr Span() = default;
    CA_HD constexpr Span(T* p, size_t n) : ptr(p), count(n) {}
    template <class U>
    Span(const std::vector<U>& v) : ptr(v.data()), count(v.size()) {}  // host only
    template <class U>
    Span(std::vector<U>& v) : ptr(v.data()), count(v.size()) {}  // host only

    CA_HD T& operator[](size_t i) const { return ptr[i]; }
    CA_HD size_t size() const { return count; }
    CA_HD bool empty() const { return count == 0; }
    CA_HD T* data() const { return ptr; }
    CA_HD T* begin() const { return ptr; }
    CA_HD T* end() const { return ptr + count; }
};

}  // namespace caustica
