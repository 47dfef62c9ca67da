// The streak command line as a user runs it: real processes, real files.

#include "image/color.h"
#include "image/image_io.h"
#include "support/temp_dir.h"

#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace streak {

namespace {

struct RunResult {
    int exitCode = -1;
    std::string out;
    std::string err;
};

std::string readFile(const std::string& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

RunResult runStreak(const test::TempDir& dir, const std::string& args) {
    const std::string out = dir.file("stdout.txt"), err = dir.file("stderr.txt");
    const std::string command = std::string(STREAK_CLI_PATH) + " " + args + " >" + out + " 2>" + err;
    const int status = std::system(command.c_str());
    RunResult r;
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = readFile(out);
    r.err = readFile(err);
    std::filesystem::remove(out);
    std::filesystem::remove(err);
    return r;
}

int countLines(const std::string& text) { return int(std::count(text.begin(), text.end(), '\n')); }

}  // namespace

TEST(Cli, ScenesListsEveryBuiltinSceneOnePerLine) {
    test::TempDir dir;
    const RunResult r = runStreak(dir, "scenes");
    EXPECT_EQ(r.exitCode, 0);
    EXPECT_EQ(countLines(r.out), 7);
    for (const char* name : {"cubes", "rotating-cube", "crossing", "twist", "fence", "pan", "translucent"})
        EXPECT_NE(r.out.find(std::string("builtin:") + name + " "), std::string::npos) << name;
}

TEST(Cli, RenderWritesImageAndStats) {
    test::TempDir dir;
    const RunResult r = runStreak(dir, "render builtin:cubes?n=20 -m stochastic --samples 2 --width 64 --height 48 -o " +
                                           dir.file("out.png") + " --stats " + dir.file("stats.json") + " --threads 1");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Image image = readImage(dir.file("out.png"));
    EXPECT_EQ(image.width(), 64);
    EXPECT_EQ(image.height(), 48);
    const std::string stats = readFile(dir.file("stats.json"));
    for (const char* key : {"\"time_ms\"", "\"render\"", "\"triangles\": 240", "\"skipped_triangles\": 0", "\"triangle_tests\""})
        EXPECT_NE(stats.find(key), std::string::npos) << key << "\n" << stats;
    // EXR output holds linear floats of the same render.
    ASSERT_EQ(runStreak(dir, "render builtin:cubes?n=20 -m stochastic --samples 2 --width 64 --height 48 --threads 1 -o " +
                                 dir.file("out.exr")).exitCode, 0);
    const Image exr = readImage(dir.file("out.exr"));
    EXPECT_NEAR(linearToSrgb(exr.at(10, 10).x), linearToSrgb(image.at(10, 10).x), 1.0 / 255);
}

TEST(Cli, BadInputIsOneLineExitTwoAndNothingWritten) {
    test::TempDir dir;
    const std::string out = dir.file("out.png");
    const std::string ok = "builtin:crossing -m accumulation --width 16 --height 16 --samples 2 ";
    {
        // The base of the cases below is itself good input: each case fails for its own reason.
        test::TempDir good;
        EXPECT_EQ(runStreak(good, "render " + ok + "-o " + good.file("ok.png")).exitCode, 0);
    }
    const std::vector<std::pair<std::string, std::string>> cases{
        {"unknown method", "render " + ok + "-m nosuch -o " + out},
        {"unknown scene", "render builtin:nosuch -o " + out},
        {"missing scene file", "render " + dir.file("missing.gltf") + " -o " + out},
        {"unknown scene option", "render builtin:cubes?size=3 -o " + out},
        {"zero width", "render builtin:crossing --width 0 -o " + out},
        {"negative height", "render builtin:crossing --height -5 -o " + out},
        {"zero samples", "render builtin:crossing -m accumulation --samples 0 -o " + out},
        {"option a method does not take", "render builtin:crossing -m motion-path --samples 4 -o " + out},
        {"malformed --option", "render builtin:crossing --option tile-cull -o " + out},
        {"bad oracle weights", "render builtin:crossing -m analytic --option oracle-weights=1,2 -o " + out},
        {"negative samples", "render builtin:crossing -m stochastic --samples -3 -o " + out},
        {"zero aa", "render " + ok + "--aa 0 -o " + out},
        {"non-numeric width", "render builtin:crossing --width abc -o " + out},
        {"bad shading", "render " + ok + "--shading toon -o " + out},
        {"bad background", "render " + ok + "--background 1,2 -o " + out},
        {"unwritable output", "render " + ok + "-o " + dir.file("no/such/folder/out.png")},
        {"unknown output format", "render " + ok + "-o " + dir.file("out.jpg")},
        {"unwritable stats", "render " + ok + "-o " + out + " --stats " + dir.file("no/such/stats.json")},
        {"unknown flag", "render " + ok + "--frobnicate -o " + out},
        {"compare missing file", "compare " + dir.file("a.png") + " " + dir.file("b.png")},
        {"no subcommand", ""},
    };
    for (const auto& [what, args] : cases) {
        SCOPED_TRACE(what);
        const RunResult r = runStreak(dir, args);
        EXPECT_EQ(r.exitCode, 2);
        EXPECT_EQ(countLines(r.err), 1) << r.err;
        EXPECT_NE(r.err.find("error"), std::string::npos) << r.err;
        EXPECT_TRUE(dir.entries().empty()) << "left a file behind";
    }
}

TEST(Cli, CompareGivesInfinityForIdenticalAndTheHandComputedPsnr) {
    test::TempDir dir;
    // a: two black pixels. b: the first pixel's red is code 51 = 0.2 encoded.
    // MSE over 2 pixels x 3 channels = 0.2^2 / 6; PSNR = 10 log10(6 / 0.04) = 10 log10(150) = 21.7609 dB.
    Image a(2, 1), b(2, 1);
    b.at(0, 0).x = srgb8ToLinear(51);
    writeImage(a, dir.file("a.png"));
    writeImage(b, dir.file("b.png"));
    const RunResult same = runStreak(dir, "compare " + dir.file("a.png") + " " + dir.file("a.png"));
    EXPECT_EQ(same.exitCode, 0);
    EXPECT_NE(same.out.find("PSNR: inf dB"), std::string::npos) << same.out;
    EXPECT_NE(same.out.find("SSIM: 1.0000"), std::string::npos) << same.out;
    const RunResult known = runStreak(dir, "compare " + dir.file("a.png") + " " + dir.file("b.png") + " --heatmap " + dir.file("h.png"));
    EXPECT_EQ(known.exitCode, 0);
    EXPECT_NE(known.out.find("PSNR: 21.7609 dB"), std::string::npos) << known.out;
    const Image heat = readImage(dir.file("h.png"));
    EXPECT_GT(heat.at(0, 0).x + heat.at(0, 0).y + heat.at(0, 0).z, 0.5f);  // the differing pixel glows
    EXPECT_EQ(heat.at(1, 0), glm::vec3(0.0f));                              // equal pixel is black
    // Different sizes cannot be compared.
    writeImage(Image(3, 1), dir.file("c.png"));
    EXPECT_EQ(runStreak(dir, "compare " + dir.file("a.png") + " " + dir.file("c.png")).exitCode, 2);
}

}  // namespace streak
