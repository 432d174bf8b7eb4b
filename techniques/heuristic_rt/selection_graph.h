#pragma once
// The selection graph of Sabino et al. 2012 §4.2-4.3 as Walewski 2019 §3.2 uses it: nodes sorted
// by cost, descending (each points to the next by cost), and each node pointing to the
// cheaper-or-equal nodes that are more relevant, those pointers ordered by relevance, descending.
// select() runs the selection loop of Walewski 2019 Listing 6 against a budget T.
#include <cstdint>
#include <vector>

namespace hybridlab {

struct SelectionNode {
    std::uint32_t object = 0;  // caller's id (a scene object index)
    double cost = 0.0;         // C, eq. (2)
    double relevance = 0.0;    // R, eq. (3)
};

// One decision of the selection loop, for tests and debugging: the highest-cost node was dropped
// (too expensive for what is left), passed over for a more relevant cheaper node, or selected.
struct SelectionStep {
    enum class Action { Dropped, PassedOver, Selected };
    Action action;
    std::uint32_t object;
};

struct SelectionResult {
    std::vector<std::uint32_t> selected;  // in selection order
    double costUsed = 0.0;
    std::vector<SelectionStep> steps;
};

class SelectionGraph {
public:
    explicit SelectionGraph(std::vector<SelectionNode> nodes);

    std::size_t size() const { return nodes_.size(); }
    // Node i in cost order (i = 0 is the most expensive; ties keep the input order).
    const SelectionNode& node(std::size_t i) const { return nodes_[i]; }
    // Positions (in cost order) of the cheaper-or-equal nodes more relevant than node i,
    // most relevant first.
    const std::vector<std::size_t>& moreRelevant(std::size_t i) const { return moreRelevant_[i]; }

    // Walewski 2019 Listing 6: while budget is left and nodes remain, take the most expensive node;
    // if it costs more than is left, drop it; else select the most relevant remaining node it
    // points to (or itself if it points to none). The selected cost never exceeds the budget.
    SelectionResult select(double budget) const;

private:
    std::vector<SelectionNode> nodes_;
    std::vector<std::vector<std::size_t>> moreRelevant_;
};

}  // namespace hybridlab
