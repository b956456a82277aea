// embree_isa.h — which SIMD instruction set Embree's kernels may use on this CPU (host only; no
// Embree header here, so nvcc-compiled units may include it).
//
// Two things decide it (docs/PERFORMANCE.md, 2026-11-28 and 2026-11-29 night):
//   - The wavefront and the whole-path kernels trace packets where the megakernel traces single
//     rays, and their images are equal only when Embree answers both alike
//     (tests/accel/intersector_packet_test.cpp). Its AVX-512 and SSE4.2 kernels do everywhere
//     measured; its AVX2 kernels did on AMD Zen 3 (0 of 3,000 rays, every equality test green)
//     but not on an Intel Cascade Lake capped at AVX2 (18 of 3,000 rays differ in the last bits of
//     t and the barycentrics; why is not known), and no Intel CPU without AVX-512 was measured.
//   - On Intel's Skylake-SP / Cascade Lake / Cooper Lake server cores (family 6, model 0x55),
//     256- and 512-bit code lowers the core's clock, which slows everything the core runs
//     meanwhile, caustica's own shading included: there Embree's SSE4.2 kernels render 1.03-1.16x
//     faster than its AVX-512 ones (medians of paired runs) and at least as fast as its AVX2 ones.
// So `auto` lets Embree take its widest kernels on CPUs with AVX-512 whose clock it does not lower
// (Ice Lake server onwards, AMD Zen 4: 16-ray packets, measured fastest there) and on AMD's CPUs
// from Zen 3 on (family 25 and later; without AVX-512 these are Zen 3, where AVX2's 8-ray packets
// render 1.02-1.17x faster than SSE4.2), and caps it at SSE4.2 everywhere else.
#pragma once

#include <string>

namespace caustica {

/// The widest instruction set Embree may use: `Auto` (the rule above), `Widest` (Embree's own
/// choice: on a CPU without AVX-512 its AVX2 kernels, whose packets and single rays differed in the
/// last bits on Intel) or `Sse42`.
enum class EmbreeIsa { Auto, Widest, Sse42 };

/// "auto", "widest" or "sse4.2"; anything else throws caustica::Error naming the choices.
EmbreeIsa parseEmbreeIsa(const std::string& name);
/// The name parseEmbreeIsa accepts for `isa`.
const char* embreeIsaName(EmbreeIsa isa);

/// The CPU's maker, from CPUID leaf 0 ("GenuineIntel", "AuthenticAMD"; anything else Other).
enum class CpuVendor { Other, Intel, Amd };

/// The processor as CPUID reports it (x86 only; elsewhere all zero / false).
struct CpuModel {
    CpuVendor vendor = CpuVendor::Other;
    unsigned family = 0;  // display family (base + extended)
    unsigned model = 0;   // display model (extended << 4 | base, for families 6 and 15)
    bool avx512 = false;  // AVX-512 F, and the OS saves its registers
};

/// This machine's CpuModel.
CpuModel hostCpuModel();

/// Whether AVX-512 code lowers `cpu`'s clock enough that Embree's SSE4.2 kernels render faster:
/// Intel family 6, model 0x55 (Skylake-SP, Cascade Lake, Cooper Lake).
bool avx512LowersClock(const CpuModel& cpu);

/// Whether Embree's AVX2 kernels were measured to answer packets as single rays on `cpu`'s kind:
/// AMD family 25 or later (Zen 3 onwards).
bool avx2PacketsMatchSingleRays(const CpuModel& cpu);

/// The cap `isa` resolves to on `cpu` (never Auto): Widest where the CPU has AVX-512 and
/// avx512LowersClock is false, or where avx2PacketsMatchSingleRays, else Sse42.
EmbreeIsa resolveEmbreeIsa(EmbreeIsa isa, const CpuModel& cpu);

/// The rtcNewDevice configuration of a resolved cap: "max_isa=sse4.2", or "" (Widest: no cap).
std::string embreeDeviceConfig(EmbreeIsa resolved);

}  // namespace caustica
