// The GL methods' alpha (the coverage behind --transparent), held to what the CPU methods' is
// (support/alpha_scene.h).

#include "support/alpha_scene.h"

#include <gtest/gtest.h>

namespace streak {

TEST(AlphaGl, EveryGlMethodGivesTheCoverageOfItsOwnColour) {
    test::expectAlphaIsCoverage("motion-path-gl", OptionMap(), 1e-5f);
    test::expectAlphaIsCoverage("accumulation-gl", test::withOption("samples", "64"), 1.0f / 64.0f + 1e-5f);
    test::expectAlphaIsCoverage("stochastic-gl", test::withOption("samples", "64"), 1.0f / 64.0f + 1e-5f);
    test::expectAlphaIsCoverage("blur-shell-gl", OptionMap(), -1.0f);
    test::expectAlphaIsCoverage("post-filter-gl", OptionMap(), -1.0f);
}

}  // namespace streak
