#include "exposure/visible_pieces.h"

#include <algorithm>

namespace streak::exposure {

void mergeAbuttingPieces(std::vector<VisiblePiece>& pieces) {
    if (pieces.size() < 2) return;
    std::sort(pieces.begin(), pieces.end(), [](const VisiblePiece& a, const VisiblePiece& b) {
        return a.triangle != b.triangle ? a.triangle < b.triangle : a.t0 < b.t0;
    });
    std::size_t merged = 0;
    for (std::size_t k = 1; k < pieces.size(); ++k) {
        VisiblePiece& last = pieces[merged];
        if (pieces[k].isWhole && last.isWhole && pieces[k].triangle == last.triangle && pieces[k].t0 == last.t1)
            last.t1 = pieces[k].t1, last.weight += pieces[k].weight;
        else
            pieces[++merged] = pieces[k];
    }
    pieces.resize(merged + 1);
}

}  // namespace streak::exposure
