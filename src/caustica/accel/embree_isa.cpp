// embree_isa.cpp — Embree's instruction-set cap (see embree_isa.h).
#include "caustica/accel/embree_isa.h"

#if defined(__x86_64__) || defined(__i386__)
#include <cpuid.h>
#endif

#include "caustica/util/error.h"

namespace caustica {

EmbreeIsa parseEmbreeIsa(const std::string& name) {
    if (name == "auto") return EmbreeIsa::Auto;
    if (name == "widest") return EmbreeIsa::Widest;
    if (name == "sse4.2") return EmbreeIsa::Sse42;
    throw Error("unknown Embree instruction set '" + name + "' (expected auto, widest or sse4.2)");
}

const char* embreeIsaName(EmbreeIsa isa) {
    switch (isa) {
        case EmbreeIsa::Auto: return "auto";
        case EmbreeIsa::Widest: return "widest";
        case EmbreeIsa::Sse42: return "sse4.2";
    }
    return "auto";
}

CpuModel hostCpuModel() {
    CpuModel cpu;
#if defined(__x86_64__) || defined(__i386__)
    unsigned eax = 0, ebx = 0, ecx = 0, edx = 0;
    if (!__get_cpuid(0, &eax, &ebx, &ecx, &edx)) return cpu;
    const unsigned maxLeaf = eax;
    if (ebx == 0x756e6547 && edx == 0x49656e69 && ecx == 0x6c65746e) cpu.vendor = CpuVendor::Intel;  // GenuineIntel
    if (ebx == 0x68747541 && edx == 0x69746e65 && ecx == 0x444d4163) cpu.vendor = CpuVendor::Amd;    // AuthenticAMD
    if (!__get_cpuid(1, &eax, &ebx, &ecx, &edx)) return cpu;
    const unsigned baseFamily = (eax >> 8) & 0xf, baseModel = (eax >> 4) & 0xf;
    const unsigned extFamily = (eax >> 20) & 0xff, extModel = (eax >> 16) & 0xf;
    cpu.family = baseFamily == 15 ? baseFamily + extFamily : baseFamily;
    cpu.model = baseFamily == 6 || baseFamily == 15 ? (extModel << 4) | baseModel : baseModel;
    // AVX-512 F (leaf 7, EBX bit 16) with the OS saving the opmask and ZMM state (XCR0 bits 5-7,
    // and SSE/AVX state, bits 1-2), read with xgetbv where OSXSAVE (leaf 1, ECX bit 27) allows it.
    const bool osxsave = (ecx >> 27) & 1;
    if (osxsave && maxLeaf >= 7) {
        unsigned xcr0Lo = 0, xcr0Hi = 0;
        __asm__("xgetbv" : "=a"(xcr0Lo), "=d"(xcr0Hi) : "c"(0));
        unsigned b7 = 0;
        __cpuid_count(7, 0, eax, b7, ecx, edx);
        cpu.avx512 = ((b7 >> 16) & 1) && (xcr0Lo & 0xe6) == 0xe6;
    }
#endif
    return cpu;
}

bool avx512LowersClock(const CpuModel& cpu) {
    return cpu.vendor == CpuVendor::Intel && cpu.family == 6 && cpu.model == 0x55;
}

bool avx2PacketsMatchSingleRays(const CpuModel& cpu) {
    return cpu.vendor == CpuVendor::Amd && cpu.family >= 25;
}

EmbreeIsa resolveEmbreeIsa(EmbreeIsa isa, const CpuModel& cpu) {
    if (isa != EmbreeIsa::Auto) return isa;
    const bool widest = (cpu.avx512 && !avx512LowersClock(cpu)) || avx2PacketsMatchSingleRays(cpu);
    return widest ? EmbreeIsa::Widest : EmbreeIsa::Sse42;
}

std::string embreeDeviceConfig(EmbreeIsa resolved) {
    return resolved == EmbreeIsa::Sse42 ? "max_isa=sse4.2" : "";
}

}  // namespace caustica
