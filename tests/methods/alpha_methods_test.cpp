// Every CPU method's alpha (the coverage behind --transparent) against closed forms and against
// its own colour over a black background (support/alpha_scene.h).

#include "support/alpha_scene.h"

#include <gtest/gtest.h>

namespace streak {

TEST(AlphaMethods, ExactMethodsGiveTheExactCoverage) {
    for (const char* method : {"motion-path", "analytic", "higher-order"}) test::expectAlphaIsCoverage(method, OptionMap(), 1e-5f);
}

TEST(AlphaMethods, SampledMethodsGiveCoverageWithinTheirSampling) {
    for (const char* method : {"accumulation", "stochastic", "embree"}) test::expectAlphaIsCoverage(method, test::withOption("samples", "64"), 1.0f / 64.0f + 1e-5f);
}

TEST(AlphaMethods, FilterMethodsGiveTheCoverageOfTheirOwnColour) {
    // Neither is exact: the shell's trail and the post-process gather spread the quad; their alpha
    // is what their colour says.
    test::expectAlphaIsCoverage("blur-shell", OptionMap(), -1.0f);
    test::expectAlphaIsCoverage("post-filter", OptionMap(), -1.0f);
}

}  // namespace streak
