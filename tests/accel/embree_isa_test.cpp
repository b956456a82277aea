// Embree's instruction-set cap (embree_isa.h): names, the CPU rule of `auto`, Embree's config.
#include <string>

#include <gtest/gtest.h>

#include "caustica/accel/embree_isa.h"
#include "caustica/util/error.h"

namespace caustica {
namespace {

TEST(EmbreeIsa, NamesRoundTripAndUnknownOnesAreRefused) {
    for (EmbreeIsa isa : {EmbreeIsa::Auto, EmbreeIsa::Widest, EmbreeIsa::Sse42})
        EXPECT_EQ(parseEmbreeIsa(embreeIsaName(isa)), isa);
    try {
        parseEmbreeIsa("avx2");
        FAIL() << "an unknown name was accepted";
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("'avx2'"), std::string::npos) << what;
        EXPECT_NE(what.find("auto, widest or sse4.2"), std::string::npos) << what;
    }
}

CpuModel cpu(bool intel, unsigned family, unsigned model, bool avx512) {
    CpuModel c;
    c.intel = intel;
    c.family = family;
    c.model = model;
    c.avx512 = avx512;
    return c;
}

TEST(EmbreeIsa, AutoTakesTheWidestOnlyOnAvx512CpusWhoseClockItDoesNotLower) {
    const CpuModel cascadeLake = cpu(true, 6, 0x55, true), iceLakeServer = cpu(true, 6, 0x6a, true),
                   emeraldRapids = cpu(true, 6, 0xcf, true), zen4 = cpu(false, 25, 0x11, true),
                   zen3 = cpu(false, 25, 0x21, false), alderLake = cpu(true, 6, 0x97, false), unknown;
    EXPECT_TRUE(avx512LowersClock(cascadeLake));
    for (const CpuModel& c : {iceLakeServer, emeraldRapids, zen4, zen3, alderLake, unknown})
        EXPECT_FALSE(avx512LowersClock(c));
    EXPECT_FALSE(avx512LowersClock(cpu(false, 6, 0x55, true)));  // model 0x55 of another vendor
    for (const CpuModel& c : {iceLakeServer, emeraldRapids, zen4})
        EXPECT_EQ(resolveEmbreeIsa(EmbreeIsa::Auto, c), EmbreeIsa::Widest);
    // AVX-512 slows the clock, or Embree's widest would be AVX2 (packets != single rays).
    for (const CpuModel& c : {cascadeLake, zen3, alderLake, unknown})
        EXPECT_EQ(resolveEmbreeIsa(EmbreeIsa::Auto, c), EmbreeIsa::Sse42);
    // A cap the user names is kept on every CPU.
    for (EmbreeIsa isa : {EmbreeIsa::Widest, EmbreeIsa::Sse42}) {
        EXPECT_EQ(resolveEmbreeIsa(isa, cascadeLake), isa);
        EXPECT_EQ(resolveEmbreeIsa(isa, zen3), isa);
        EXPECT_EQ(resolveEmbreeIsa(isa, emeraldRapids), isa);
    }
}

TEST(EmbreeIsa, DeviceConfigNamesEmbreesIsa) {
    EXPECT_EQ(embreeDeviceConfig(EmbreeIsa::Widest), "");
    EXPECT_EQ(embreeDeviceConfig(EmbreeIsa::Sse42), "max_isa=sse4.2");
}

TEST(EmbreeIsa, HostCpuIsIdentifiedOnX86) {
#if defined(__x86_64__)
    const CpuModel host = hostCpuModel();
    EXPECT_GE(host.family, 6u);  // every x86-64 CPU: family 6 (Intel), 15 + n (AMD)
#else
    GTEST_SKIP() << "CPUID is x86 only";
#endif
}

}  // namespace
}  // namespace caustica
