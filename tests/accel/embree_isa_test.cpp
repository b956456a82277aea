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

CpuModel cpu(CpuVendor vendor, unsigned family, unsigned model, bool avx512) {
    CpuModel c;
    c.vendor = vendor;
    c.family = family;
    c.model = model;
    c.avx512 = avx512;
    return c;
}

TEST(EmbreeIsa, AutoTakesTheWidestOnAvx512CpusWhoseClockItDoesNotLowerAndOnZen3) {
    constexpr CpuVendor intel = CpuVendor::Intel, amd = CpuVendor::Amd;
    const CpuModel cascadeLake = cpu(intel, 6, 0x55, true), iceLakeServer = cpu(intel, 6, 0x6a, true),
                   emeraldRapids = cpu(intel, 6, 0xcf, true), zen4 = cpu(amd, 25, 0x11, true),
                   zen3 = cpu(amd, 25, 0x01, false), zen2 = cpu(amd, 23, 0x31, false),
                   alderLake = cpu(intel, 6, 0x97, false), otherFamily25 = cpu(CpuVendor::Other, 25, 0x01, false),
                   unknown;
    EXPECT_TRUE(avx512LowersClock(cascadeLake));
    for (const CpuModel& c : {iceLakeServer, emeraldRapids, zen4, zen3, alderLake, unknown})
        EXPECT_FALSE(avx512LowersClock(c));
    EXPECT_FALSE(avx512LowersClock(cpu(amd, 6, 0x55, true)));  // model 0x55 of another vendor
    EXPECT_TRUE(avx2PacketsMatchSingleRays(zen3));
    EXPECT_TRUE(avx2PacketsMatchSingleRays(cpu(amd, 26, 0x02, false)));  // later AMD families too
    for (const CpuModel& c : {zen2, alderLake, otherFamily25, cascadeLake, unknown})
        EXPECT_FALSE(avx2PacketsMatchSingleRays(c));
    for (const CpuModel& c : {iceLakeServer, emeraldRapids, zen4, zen3})
        EXPECT_EQ(resolveEmbreeIsa(EmbreeIsa::Auto, c), EmbreeIsa::Widest);
    // AVX-512 slows the clock, or Embree's widest would be AVX2 where its packets were not
    // measured (or measured not) to answer as its single rays.
    for (const CpuModel& c : {cascadeLake, zen2, alderLake, otherFamily25, unknown})
        EXPECT_EQ(resolveEmbreeIsa(EmbreeIsa::Auto, c), EmbreeIsa::Sse42);
    // A cap the user names is kept on every CPU.
    for (EmbreeIsa isa : {EmbreeIsa::Widest, EmbreeIsa::Sse42}) {
        EXPECT_EQ(resolveEmbreeIsa(isa, cascadeLake), isa);
        EXPECT_EQ(resolveEmbreeIsa(isa, zen3), isa);
        EXPECT_EQ(resolveEmbreeIsa(isa, zen2), isa);
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
