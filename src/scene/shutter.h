#pragma once

#include <glm/vec2.hpp>

#include <string>
#include <vector>

namespace streak {

// ShutterCurve is the shape of the shutter's opening over its open interval x in [0, 1]: a weight
// w(x) >= 0, piecewise linear through its points (Blender's shutter curve), normalised so that
// it integrates to 1. Exposure methods use its integral (exposureAt) to weigh time spans and its
// inverse (positionOf) to place time samples where the shutter is open.
class ShutterCurve {
public:
    ShutterCurve();  // box: w = 1

    // box | triangle | trapezoid:A (ramps of A in (0, 0.5] at both ends) | T0:W0,T1:W1,... (points
    // with T0 = 0 < T1 < ... < Tn = 1, W >= 0, not all 0; at most kMaxPoints). Throws Error.
    static ShutterCurve parse(const std::string& text);
    static constexpr int kMaxPoints = 32;

    bool isBox() const { return m_isBox; }
    const std::string& name() const { return m_name; }
    const std::vector<glm::vec2>& points() const { return m_points; }  ///< (x, normalised w)

    float weightAt(float x) const;
    // The integral of w over [0, x], x clamped to [0, 1]: closed form (piecewise quadratic).
    double exposureAt(double x) const;
    // The x with exposureAt(x) = u, u in [0, 1]; within a flat zero stretch, its start.
    double positionOf(double u) const;

private:
    std::string m_name = "box";
    bool m_isBox = true;
    std::vector<glm::vec2> m_points;
    std::vector<double> m_cumulative;  ///< exposureAt(points[i].x)
};

// ShutterWindow is what one image row sees of the shutter: the stretch [start, start + length]
// of shutter time t in [0, 1] with the curve over it. exposureAt(t) is the share of the row's
// exposure before t; timeAt(u) its inverse. The whole shutter under a box curve is the identity
// and takes the exact identity paths, so a box shutter renders bit for bit as before.
struct ShutterWindow {
    float start = 0.0f;
    float length = 1.0f;
    const ShutterCurve* curve = nullptr;  ///< null: box

    bool isIdentity() const { return start == 0.0f && length == 1.0f && (!curve || curve->isBox()); }
    float exposureAt(float t) const;
    // The share of the row's exposure in [t0, t1]: t1 - t0 for the identity.
    float measure(float t0, float t1) const { return isIdentity() ? t1 - t0 : exposureAt(t1) - exposureAt(t0); }
    float timeAt(float u) const;
    // The time a fraction f of the way through [t0, t1] by exposure: where span taps go.
    float timeBetween(float t0, float t1, float f) const;
};

// Where the shutter sits around the frame (Blender's shutter position): open over [F, F + S],
// [F - S/2, F + S/2] or [F - S, F] frames.
enum class ShutterPosition { Start, Center, End };
ShutterPosition parseShutterPosition(const std::string& text);
const char* shutterPositionName(ShutterPosition position);
// The frame the shutter opens at for frame F and S frames open.
double shutterOpenFrame(ShutterPosition position, double frame, double shutterFrames);

// Shutter is how the scene's shutter interval t in [0, 1] is exposed: the curve and, for a
// rolling shutter, the share D of the interval each row is open (Blender's rolling shutter
// duration): row y of H opens at (1 - D) y / (H - 1), top row first, and stays open for D, the
// curve applying within its window. D = 1 is a global shutter.
struct Shutter {
    ShutterCurve curve;
    float rollingDuration = 1.0f;

    bool isRolling() const { return rollingDuration < 1.0f; }
    bool isBox() const { return curve.isBox() && !isRolling(); }  ///< every row sees [0, 1] evenly
    ShutterWindow rowWindow(int row, int height) const;
    std::string describe() const;
};

// Throws Error unless D is in (0, 1].
float checkRollingDuration(double duration);

}  // namespace streak
