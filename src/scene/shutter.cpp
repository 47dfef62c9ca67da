#include "scene/shutter.h"

#include "util/error.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace streak {

namespace {

double parseNumber(const std::string& text, const std::string& what) {
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(value))
        throw Error("--shutter-curve: " + what + " must be a number, got '" + text + "'");
    return value;
}

std::vector<glm::vec2> pointsOf(const std::string& text) {
    if (text == "box") return {{0.0f, 1.0f}, {1.0f, 1.0f}};
    if (text == "triangle") return {{0.0f, 0.0f}, {0.5f, 1.0f}, {1.0f, 0.0f}};
    if (text.rfind("trapezoid:", 0) == 0) {
        const double a = parseNumber(text.substr(10), "trapezoid's ramp");
        if (!(a > 0.0 && a <= 0.5)) throw Error("--shutter-curve: trapezoid's ramp must be in (0, 0.5], got '" + text.substr(10) + "'");
        if (a == 0.5) return {{0.0f, 0.0f}, {0.5f, 1.0f}, {1.0f, 0.0f}};
        return {{0.0f, 0.0f}, {float(a), 1.0f}, {float(1.0 - a), 1.0f}, {1.0f, 0.0f}};
    }
    if (text.find(':') == std::string::npos)
        throw Error("--shutter-curve must be box, triangle, trapezoid:A or T0:W0,T1:W1,..., got '" + text + "'");
    std::vector<glm::vec2> points;
    std::stringstream list(text);
    std::string item;
    while (std::getline(list, item, ',')) {
        const std::size_t colon = item.find(':');
        if (colon == std::string::npos) throw Error("--shutter-curve: point '" + item + "' is not T:W");
        points.emplace_back(float(parseNumber(item.substr(0, colon), "T")), float(parseNumber(item.substr(colon + 1), "W")));
    }
    if (points.size() < 2 || int(points.size()) > ShutterCurve::kMaxPoints)
        throw Error("--shutter-curve needs 2 to " + std::to_string(ShutterCurve::kMaxPoints) + " points T:W, got " +
                    std::to_string(points.size()));
    if (points.front().x != 0.0f || points.back().x != 1.0f) throw Error("--shutter-curve: the points must run from T = 0 to T = 1");
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (i > 0 && !(points[i].x > points[i - 1].x)) throw Error("--shutter-curve: the points' T must increase");
        if (points[i].y < 0.0f) throw Error("--shutter-curve: a weight W is negative");
    }
    return points;
}

}  // namespace

ShutterCurve::ShutterCurve() : m_points{{0.0f, 1.0f}, {1.0f, 1.0f}}, m_cumulative{0.0, 1.0} {}

ShutterCurve ShutterCurve::parse(const std::string& text) {
    ShutterCurve curve;
    curve.m_name = text;
    curve.m_points = pointsOf(text);
    double area = 0.0;
    for (std::size_t i = 1; i < curve.m_points.size(); ++i)
        area += 0.5 * (double(curve.m_points[i].y) + curve.m_points[i - 1].y) * (double(curve.m_points[i].x) - curve.m_points[i - 1].x);
    if (!(area > 0.0)) throw Error("--shutter-curve: the weights are all 0 (the shutter never opens)");
    curve.m_isBox = true;
    for (glm::vec2& p : curve.m_points) {
        p.y = float(p.y / area);
        curve.m_isBox = curve.m_isBox && p.y == 1.0f;
    }
    curve.m_cumulative.assign(1, 0.0);
    for (std::size_t i = 1; i < curve.m_points.size(); ++i) {
        const glm::dvec2 a = curve.m_points[i - 1], b = curve.m_points[i];
        curve.m_cumulative.push_back(curve.m_cumulative.back() + 0.5 * (a.y + b.y) * (b.x - a.x));
    }
    curve.m_cumulative.back() = 1.0;
    return curve;
}

float ShutterCurve::weightAt(float x) const {
    if (!(x >= 0.0f && x <= 1.0f)) return 0.0f;
    const auto hi = std::upper_bound(m_points.begin() + 1, m_points.end() - 1, x, [](float v, const glm::vec2& p) { return v < p.x; });
    const glm::vec2 a = *(hi - 1), b = *hi;
    return a.y + (b.y - a.y) * (x - a.x) / (b.x - a.x);
}

double ShutterCurve::exposureAt(double x) const {
    if (!(x > 0.0)) return 0.0;
    if (x >= 1.0) return 1.0;
    if (m_isBox) return x;
    const auto hi = std::upper_bound(m_points.begin() + 1, m_points.end() - 1, x, [](double v, const glm::vec2& p) { return v < p.x; });
    const std::size_t i = std::size_t(hi - m_points.begin()) - 1;
    const glm::dvec2 a = m_points[i], b = m_points[i + 1];
    const double h = x - a.x, slope = (b.y - a.y) / (b.x - a.x);
    return std::min(1.0, m_cumulative[i] + h * (a.y + 0.5 * slope * h));
}

double ShutterCurve::positionOf(double u) const {
    if (!(u > 0.0)) u = 0.0;
    if (u >= 1.0) u = 1.0;
    if (m_isBox) return u;
    // The segment whose exposure reaches past u, then the root of a h^2 + b h = u - C(a.x).
    std::size_t i = std::size_t(std::upper_bound(m_cumulative.begin(), m_cumulative.end(), u) - m_cumulative.begin());
    i = std::clamp<std::size_t>(i, 1, m_points.size() - 1) - 1;
    const glm::dvec2 a = m_points[i], b = m_points[i + 1];
    const double slope = (b.y - a.y) / (b.x - a.x), rest = u - m_cumulative[i];
    const double qa = 0.5 * slope, qb = a.y;
    double h;
    if (!(rest > 0.0)) h = 0.0;
    else if (std::abs(qa) < 1e-12) h = qb > 0.0 ? rest / qb : 0.0;
    else h = 2.0 * rest / (qb + std::sqrt(std::max(0.0, qb * qb + 4.0 * qa * rest)));
    return std::clamp(a.x + h, a.x, b.x);
}

float ShutterWindow::exposureAt(float t) const {
    const double x = (double(t) - start) / length;
    return float(curve ? curve->exposureAt(x) : std::clamp(x, 0.0, 1.0));
}

float ShutterWindow::timeAt(float u) const {
    if (isIdentity()) return u;
    const double x = curve ? curve->positionOf(u) : std::clamp(double(u), 0.0, 1.0);
    return float(std::min(1.0, start + length * x));
}

float ShutterWindow::timeBetween(float t0, float t1, float f) const {
    if (isIdentity()) return t0 + f * (t1 - t0);
    const float u0 = exposureAt(t0), u1 = exposureAt(t1);
    if (!(u1 > u0)) return t0 + f * (t1 - t0);
    return std::clamp(timeAt(u0 + f * (u1 - u0)), t0, t1);
}

ShutterPosition parseShutterPosition(const std::string& text) {
    if (text == "start") return ShutterPosition::Start;
    if (text == "center") return ShutterPosition::Center;
    if (text == "end") return ShutterPosition::End;
    throw Error("--shutter-position must be start, center or end, got '" + text + "'");
}

const char* shutterPositionName(ShutterPosition position) {
    switch (position) {
    case ShutterPosition::Center: return "center";
    case ShutterPosition::End: return "end";
    default: return "start";
    }
}

double shutterOpenFrame(ShutterPosition position, double frame, double shutterFrames) {
    switch (position) {
    case ShutterPosition::Center: return frame - 0.5 * shutterFrames;
    case ShutterPosition::End: return frame - shutterFrames;
    default: return frame;
    }
}

ShutterWindow Shutter::rowWindow(int row, int height) const {
    ShutterWindow window;
    window.curve = &curve;
    if (!isRolling()) return window;
    window.length = rollingDuration;
    window.start = height > 1 ? (1.0f - rollingDuration) * float(row) / float(height - 1) : 0.0f;
    return window;
}

std::string Shutter::describe() const {
    std::ostringstream out;
    out << curve.name();
    if (isRolling()) out << ", rolling " << rollingDuration;
    return out.str();
}

float checkRollingDuration(double duration) {
    if (!(duration > 0.0 && duration <= 1.0))
        throw Error("--rolling-shutter must be in (0, 1] (the share of the shutter each row is open), got " + std::to_string(duration));
    return float(duration);
}

}  // namespace streak
