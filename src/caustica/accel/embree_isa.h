// embree_isa.h — which SIMD instruction set Embree's kernels may use on this CPU (host only; no
// Embree header here, so nvcc-compiled units may include it).
//
// Two things decide it (docs/PERFORMANCE.md, 2026-11-28):
//   - Embree's AVX2 kernels answer a packet query in other last bits than a single-ray query
//     (tests/accel/intersector_packet_test.cpp); its AVX-512 and SSE4.2 kernels answer both alike.
//     The wavefront and the whole-path kernels trace packets where the megakernel traces single
//     rays, and their images are equal only when both answer alike.
//   - On Intel's Skylake-SP / Cascade Lake / Cooper Lake server cores (family 6, model 0x55),
//     256- and 512-bit code lowers the core's clock, which slows everything the core runs
//     meanwhile, caustica's own shading included: there Embree's SSE4.2 kernels render 1.03-1.16x
//     faster than its AVX-512 ones (medians of paired runs) and at least as fast as its AVX2 ones.
// So `auto` lets Embree take its widest kernels on CPUs with AVX-512 whose clock it does not lower
// (Ice Lake server onwards, AMD Zen 4: 16-ray packets, measured fastest there) and caps it at
// SSE4.2 everywhere else.
#pragma once

#include <string>

namespace caustica {

/// The widest instruction set Embree may use: `Auto` (the rule above), `Widest` (Embree's own
/// choice: on a CPU without AVX-512 its AVX2 kernels, whose packets and single rays differ in the
/// last bits) or `Sse42`.
enum class EmbreeIsa { Auto, Widest, Sse42 };

/// "auto", "widest" or "sse4.2"; anything else throws caustica::Error naming the choices.
EmbreeIsa parseEmbreeIsa(const std::string& name);
/// The name parseEmbreeIsa accepts for `isa`.
const char* embreeIsaName(EmbreeIsa isa);

/// The processor as CPUID reports it (x86 only; elsewhere all zero / false).
struct CpuModel {
    bool intel = false;
    unsigned family = 0;  // display family (base + extended)
    unsigned model = 0;   // display model (extended << 4 | base, for families 6 and 15)
    bool avx512 = false;  // AVX-512 F, and the OS saves its registers
};

/// This machine's CpuModel.
CpuModel hostCpuModel();

/// Whether AVX-512 code lowers `cpu`'s clock enough that Embree's SSE4.2 kernels render faster:
/// Intel family 6, model 0x55 (Skylake-SP, Cascade Lake, Cooper Lake).
bool avx512LowersClock(const CpuModel& cpu);

/// The cap `isa` resolves to on `cpu` (never Auto): Widest where the CPU has AVX-512 and
/// avx512LowersClock is false, else Sse42.
EmbreeIsa resolveEmbreeIsa(EmbreeIsa isa, const CpuModel& cpu);

/// The rtcNewDevice configuration of a resolved cap: "max_isa=sse4.2", or "" (Widest: no cap).
std::string embreeDeviceConfig(EmbreeIsa resolved);

}  // namespace caustica
