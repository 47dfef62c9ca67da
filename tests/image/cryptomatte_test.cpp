// Cryptomatte's IDs, keys, manifest and channel names against the specification's own examples.

#include "image/cryptomatte.h"

#include <gtest/gtest.h>

#include <cmath>

namespace streak {

TEST(Cryptomatte, MurmurHash3MatchesItsPublishedValues) {
    EXPECT_EQ(murmurHash3(""), 0u);
    EXPECT_EQ(murmurHash3("", 1), 0x514e28b7u);
    EXPECT_EQ(murmurHash3("hello"), 0x248bfa47u);
    EXPECT_EQ(murmurHash3("The quick brown fox jumps over the lazy dog"), 0x2e4ff723u);
}

TEST(Cryptomatte, IdsAndKeysAreTheSpecificationsExamples) {
    // Cryptomatte 1.1's manifest and metadata examples.
    EXPECT_EQ(cryptomatteHex(cryptomatteId("bunny")), "13851a76");
    EXPECT_EQ(cryptomatteHex(cryptomatteId("default")), "42c9679f");
    EXPECT_EQ(cryptomatteHex(cryptomatteId("bunny_porcelain_mat")), "b24b26d4");
    EXPECT_EQ(cryptomatteManifest({"bunny", "default"}), R"({"bunny":"13851a76","default":"42c9679f"})");
    // An ID is never a NaN, an infinity or a denormal, whatever the hash's exponent bits.
    for (const char* name : {"a", "b", "wall", "sweeper", "node 12", ""}) {
        const float id = cryptomatteId(name);
        EXPECT_TRUE(std::isnormal(id)) << name;
    }
}

TEST(Cryptomatte, ChannelsFollowTheLayerNaming) {
    EXPECT_EQ(cryptomatteChannel("CryptoObject", 0, false), "CryptoObject00.r");
    EXPECT_EQ(cryptomatteChannel("CryptoObject", 0, true), "CryptoObject00.g");
    EXPECT_EQ(cryptomatteChannel("CryptoObject", 1, false), "CryptoObject00.b");
    EXPECT_EQ(cryptomatteChannel("CryptoObject", 1, true), "CryptoObject00.a");
    EXPECT_EQ(cryptomatteChannel("CryptoMaterial", 5, true), "CryptoMaterial02.a");
    EXPECT_EQ(cryptomatteLayers(6), 3);
    EXPECT_EQ(cryptomatteLayers(3), 2);
    EXPECT_EQ(cryptomatteKey("CryptoObject").size(), 7u);
}

}  // namespace streak
