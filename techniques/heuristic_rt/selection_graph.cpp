#include "techniques/heuristic_rt/selection_graph.h"

#include <algorithm>

namespace hybridlab {

SelectionGraph::SelectionGraph(std::vector<SelectionNode> nodes) : nodes_(std::move(nodes)) {
    std::stable_sort(nodes_.begin(), nodes_.end(), [](const SelectionNode& a, const SelectionNode& b) { return a.cost > b.cost; });
    const std::size_t n = nodes_.size();
    moreRelevant_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t j = 0; j < n; ++j) {
            if (j != i && nodes_[j].cost <= nodes_[i].cost && nodes_[j].relevance > nodes_[i].relevance) moreRelevant_[i].push_back(j);
        }
        std::stable_sort(moreRelevant_[i].begin(), moreRelevant_[i].end(),
                         [&](std::size_t a, std::size_t b) { return nodes_[a].relevance > nodes_[b].relevance; });
    }
}

SelectionResult SelectionGraph::select(double budget) const {
    SelectionResult r;
    std::vector<bool> removed(nodes_.size(), false);
    double left = budget;
    std::size_t head = 0;  // the most expensive node not yet removed
    auto advance = [&] {
        while (head < nodes_.size() && removed[head]) ++head;
    };
    advance();
    while (left > 0.0 && head < nodes_.size()) {
        const SelectionNode& cur = nodes_[head];
        if (cur.cost > left) {
            r.steps.push_back({SelectionStep::Action::Dropped, cur.object});
            removed[head] = true;
        } else {
            std::size_t pick = head;
            for (std::size_t j : moreRelevant_[head]) {
                if (!removed[j]) {  // pointers are ordered by relevance: the first remaining is the best
                    pick = j;
                    break;
                }
            }
            if (pick != head) r.steps.push_back({SelectionStep::Action::PassedOver, cur.object});
            r.steps.push_back({SelectionStep::Action::Selected, nodes_[pick].object});
            r.selected.push_back(nodes_[pick].object);
            r.costUsed += nodes_[pick].cost;
            left -= nodes_[pick].cost;
            removed[pick] = true;
        }
        advance();
    }
    return r;
}

}  // namespace hybridlab
