// Intervals in the depth-time plane and their visibility: the GLSL twins of
// methods/motion_path/interval.cpp (Hong & Oh's crossing split, four tests and selection sort)
// and resolve.cpp (n-bit time masks; per-slice transmittance for translucent intervals).

struct Interval {
    float t0, t1;
    float depth0, depth1;
    uint segment;
    vec4 color;  // translucent intervals: mean colour and alpha over the span
};

float minDepth(Interval i) { return min(i.depth0, i.depth1); }
float maxDepth(Interval i) { return max(i.depth0, i.depth1); }
float depthAt(Interval i, float t) { return i.t1 > i.t0 ? i.depth0 + (i.depth1 - i.depth0) * (t - i.t0) / (i.t1 - i.t0) : i.depth0; }
float depthTolerance(Interval a, Interval b) { return 1e-6 * (maxDepth(a) + maxDepth(b)); }

bool splitAtCrossing(inout Interval a, inout Interval b, out Interval aTail, out Interval bTail) {
    aTail = a;
    bTail = b;
    float ts = max(a.t0, b.t0), te = min(a.t1, b.t1);
    if (!(ts < te)) return false;
    float ds = depthAt(a, ts) - depthAt(b, ts), de = depthAt(a, te) - depthAt(b, te);
    float eps = depthTolerance(a, b);
    if (!((ds > eps && de < -eps) || (ds < -eps && de > eps))) return false;
    float t = ts + (te - ts) * ds / (ds - de);
    if (!(t > a.t0 && t < a.t1 && t > b.t0 && t < b.t1)) return false;
    float depthA = depthAt(a, t), depthB = depthAt(b, t);
    a.t1 = t, a.depth1 = depthA;
    aTail.t0 = t, aTail.depth0 = depthA;
    b.t1 = t, b.depth1 = depthB;
    bTail.t0 = t, bTail.depth0 = depthB;
    return true;
}

bool canStayBefore(Interval h, Interval k) {
    float eps = depthTolerance(h, k);
    if (maxDepth(h) <= minDepth(k) + eps) return true;
    float ts = max(h.t0, k.t0), te = min(h.t1, k.t1);
    if (!(ts < te)) return true;
    if (depthAt(k, ts) >= depthAt(h, ts) - eps && depthAt(k, te) >= depthAt(h, te) - eps) return true;
    return depthAt(h, ts) <= depthAt(k, ts) + eps && depthAt(h, te) <= depthAt(k, te) + eps;
}

// Time masks of up to 256 bits as uint[8]; slice i is [i/n, (i+1)/n).
const int kMaskWords = 8;

void spanMask(float t0, float t1, int numBits, out uint mask[kMaskWords]) {
    int first = max(0, int(ceil(double(t0) * double(numBits) - 0.5)));
    int end = min(numBits, int(ceil(double(t1) * double(numBits) - 0.5)));
    for (int w = 0; w < kMaskWords; ++w) {
        int lo = max(first, w * 32), hi = min(end, w * 32 + 32);
        mask[w] = lo >= hi ? 0u : (hi - lo == 32 ? 0xffffffffu : ((1u << uint(hi - lo)) - 1u)) << uint(lo - w * 32);
    }
}

// The slices of the sample row's exposure (g_window) that [t0, t1] covers (TimeMask::exposed).
void exposedMask(float t0, float t1, int numBits, out uint mask[kMaskWords]) {
    if (g_window.isIdentity) spanMask(t0, t1, numBits, mask);
    else spanMask(exposureAt(g_window, t0), exposureAt(g_window, t1), numBits, mask);
}
