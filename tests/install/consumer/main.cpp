// consumer SCENE OUT.exr: SCENE rendered with analytic at 64x48, as `streak render SCENE -m
// analytic --width 64 --height 48` renders it.
#include <streak/streak.h>

#include <cstdio>

int main(int argc, char** argv) {
    if (argc != 3) return 2;
    try {
        streak::api::LoadOptions load;
        load.width = 64, load.height = 48;
        const streak::api::Scene scene = streak::api::Scene::load(argv[1], load);
        streak::api::RenderSettings settings;
        settings.method = "analytic";
        settings.width = 64, settings.height = 48;
        streak::api::writeImage(streak::api::render(scene, settings).image, argv[2]);
    } catch (const streak::Error& e) {
        std::fprintf(stderr, "consumer: %s\n", e.what());
        return 2;
    }
    return 0;
}
