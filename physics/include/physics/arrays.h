// Flat, aligned arrays: one per axis (structure of arrays), as the pair loop wants them.
#pragma once

#include <cstddef>
#include <new>
#include <vector>

#include "physics/vec3.h"

namespace softbody {

template <class T, std::size_t Alignment = 64>
struct AlignedAllocator {
    using value_type = T;
    template <class U>
    struct rebind {
        using other = AlignedAllocator<U, Alignment>;
    };
    AlignedAllocator() = default;
    template <class U>
    AlignedAllocator(const AlignedAllocator<U, Alignment>&) {}
    T* allocate(std::size_t n) {
        return static_cast<T*>(::operator new(n * sizeof(T), std::align_val_t(Alignment)));
    }
    void deallocate(T* p, std::size_t) { ::operator delete(p, std::align_val_t(Alignment)); }
    template <class U>
    bool operator==(const AlignedAllocator<U, Alignment>&) const { return true; }
};

using FloatArray = std::vector<float, AlignedAllocator<float>>;

// N vectors stored as three arrays x[], y[], z[].
struct Vec3Array {
    FloatArray x, y, z;

    void resize(std::size_t n, float value = 0.0f) {
        x.assign(n, value);
        y.assign(n, value);
        z.assign(n, value);
    }
    std::size_t size() const { return x.size(); }
    Vec3 operator[](std::size_t i) const { return {x[i], y[i], z[i]}; }
    void set(std::size_t i, const Vec3& v) {
        x[i] = v.x;
        y[i] = v.y;
        z[i] = v.z;
    }
    void add(std::size_t i, const Vec3& v) {
        x[i] += v.x;
        y[i] += v.y;
        z[i] += v.z;
    }
};

}  // namespace softbody
