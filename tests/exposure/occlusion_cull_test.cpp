#include "exposure/occlusion_cull.h"

#include "util/random.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace streak::exposure {

namespace {

ExposureInterval interval(float t0, float t1, float depth0, float depth1, float alpha = 1.0f, std::uint32_t source = 0) {
    ExposureInterval x;
    x.t0 = t0, x.t1 = t1, x.depth0 = depth0, x.depth1 = depth1, x.alpha = alpha, x.source = source;
    return x;
}

std::vector<std::uint32_t> sources(const std::vector<ExposureInterval>& list) {
    std::vector<std::uint32_t> out;
    for (const ExposureInterval& x : list) out.push_back(x.source);
    return out;
}

}  // namespace

// Two opaque occluders abutting at t = 0.5 cover [0, 1] in front: everything wholly behind
// both goes, in order; what reaches nearer than an occluder's far end, pokes out of the covered
// time, or is only behind a translucent surface stays.
TEST(OcclusionCull, DropsWhatNearerOpaqueSpansCoverAndKeepsTheRest) {
    std::vector<ExposureInterval> list = {
        interval(0.0f, 0.5f, 1.0f, 2.0f, 1.0f, 0),   // occluder, depth up to 2
        interval(0.5f, 1.0f, 1.5f, 1.0f, 1.0f, 1),   // occluder, depth up to 1.5
        interval(0.1f, 0.9f, 3.0f, 4.0f, 1.0f, 2),   // behind both: hidden
        interval(0.2f, 0.3f, 1.9f, 5.0f, 1.0f, 3),   // nearer than occluder 0's far end: kept
        interval(0.6f, 0.7f, 2.5f, 2.5f, 0.5f, 4),   // translucent, behind: hidden
        interval(0.0f, 1.0f, 0.5f, 0.5f, 0.3f, 5),   // translucent in front: kept, occludes nothing
        interval(0.55f, 0.95f, 9.0f, 9.0f, 1.0f, 6), // behind occluder 1: hidden
    };
    OcclusionScratch scratch;
    EXPECT_EQ(cullHiddenIntervals(list, scratch), 3u);
    EXPECT_EQ(sources(list), (std::vector<std::uint32_t>{0, 1, 3, 5}));

    // A gap in the cover keeps what spans it.
    std::vector<ExposureInterval> gap = {interval(0.0f, 0.4f, 1.0f, 1.0f, 1.0f, 0), interval(0.6f, 1.0f, 1.0f, 1.0f, 1.0f, 1),
                                         interval(0.3f, 0.7f, 2.0f, 2.0f, 1.0f, 2), interval(0.1f, 0.3f, 2.0f, 2.0f, 1.0f, 3)};
    EXPECT_EQ(cullHiddenIntervals(gap, scratch), 1u);
    EXPECT_EQ(sources(gap), (std::vector<std::uint32_t>{0, 1, 2}));
}

// Against the resolves themselves, on random lists: every dropped interval had no share, and the
// rest keep their shares and the background's (to rounding: the pieces are cut differently).
TEST(OcclusionCull, DroppedIntervalsHadNoShareAndTheRestKeepTheirs) {
    Rng rng(7);
    OcclusionScratch scratch;
    int dropped = 0;
    for (int trial = 0; trial < 400; ++trial) {
        const bool translucent = trial % 2 == 1;
        std::vector<ExposureInterval> list;
        const int n = 2 + int(rng.uniform() * 30.0f);
        for (int i = 0; i < n; ++i) {
            const float a = rng.uniform(), b = rng.uniform();
            const float alpha = translucent && rng.uniform() < 0.4f ? 0.25f + 0.5f * rng.uniform() : 1.0f;
            list.push_back(interval(std::min(a, b), std::max(a, b), 1.0f + 4.0f * rng.uniform(), 1.0f + 4.0f * rng.uniform(), alpha,
                                    std::uint32_t(i)));
        }
        auto resolve = [&](const std::vector<ExposureInterval>& l, std::vector<float>& w) {
            w.assign(l.size(), 0.0f);
            return translucent ? resolveTranslucent(l, w) : resolveOpaque(l, w);
        };
        std::vector<float> before, after;
        const float backgroundBefore = resolve(list, before);
        std::vector<ExposureInterval> culled = list;
        dropped += int(cullHiddenIntervals(culled, scratch));
        const float backgroundAfter = resolve(culled, after);
        EXPECT_NEAR(backgroundAfter, backgroundBefore, 1e-5f);
        std::size_t k = 0;
        for (std::size_t i = 0; i < list.size(); ++i) {
            if (k < culled.size() && culled[k].source == list[i].source) {
                EXPECT_NEAR(after[k], before[i], 1e-5f) << "trial " << trial << " interval " << i;
                ++k;
            } else {
                EXPECT_EQ(before[i], 0.0f) << "trial " << trial << " dropped interval " << i << " had a share";
            }
        }
        EXPECT_EQ(k, culled.size());
    }
    EXPECT_GT(dropped, 200);  // the test exercises the cull, not only the keeping
}

}  // namespace streak::exposure
