// The selection graph (Sabino et al. 2012 §4.2-4.3) and the selection loop of Walewski 2019
// Listing 6, on the papers' own examples and on random graphs.
#include <algorithm>
#include <limits>
#include <random>
#include <set>

#include <gtest/gtest.h>

#include "techniques/heuristic_rt/heuristic.h"
#include "techniques/heuristic_rt/selection_graph.h"

namespace hybridlab {
namespace {

using Action = SelectionStep::Action;

std::vector<std::uint32_t> pointedObjects(const SelectionGraph& g, std::uint32_t object) {
    for (std::size_t i = 0; i < g.size(); ++i) {
        if (g.node(i).object != object) continue;
        std::vector<std::uint32_t> out;
        for (std::size_t j : g.moreRelevant(i)) out.push_back(g.node(j).object);
        return out;
    }
    return {};
}

TEST(SelectionGraph, SabinoTable1Figure3) {
    // Sabino 2012 Table 1: nodes 9 to 22 with their costs C and relevances R.
    const std::vector<std::uint32_t> id = {9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20, 21, 22};
    const std::vector<double> C = {20, 19, 18, 17, 16, 15, 14, 14, 13, 12, 11, 10, 9, 9};
    const std::vector<double> R = {22, 21, 18, 30, 31, 32, 28, 27, 9, 29, 1, 20, 4, 3};
    std::vector<SelectionNode> nodes;
    for (std::size_t i = 0; i < id.size(); ++i) nodes.push_back({id[i], C[i], R[i]});
    SelectionGraph g(nodes);
    // Node 11 points to the cheaper nodes more relevant than 18, most relevant first.
    EXPECT_EQ(pointedObjects(g, 11), (std::vector<std::uint32_t>{14, 13, 12, 18, 15, 16, 20}));
    // Budget 18: nodes 9 and 10 are dropped, node 11 is passed over, node 14 is chosen (Figure 3).
    SelectionResult r = g.select(18.0);
    ASSERT_GE(r.steps.size(), 4u);
    EXPECT_EQ(r.steps[0].action, Action::Dropped);
    EXPECT_EQ(r.steps[0].object, 9u);
    EXPECT_EQ(r.steps[1].action, Action::Dropped);
    EXPECT_EQ(r.steps[1].object, 10u);
    EXPECT_EQ(r.steps[2].action, Action::PassedOver);
    EXPECT_EQ(r.steps[2].object, 11u);
    EXPECT_EQ(r.steps[3].action, Action::Selected);
    EXPECT_EQ(r.steps[3].object, 14u);
    // 3 left after node 14 (cost 15): nothing else fits.
    EXPECT_EQ(r.selected, (std::vector<std::uint32_t>{14}));
    EXPECT_EQ(r.costUsed, 15.0);
}

TEST(SelectionGraph, WalewskiFigure4Narrative) {
    // Built to match Walewski 2019 Figure 4's narrative with budget 400: node 3 is the first
    // cheaper than 400 (nodes 1 and 2 leave the graph), it points to node 4 next by cost and to
    // nodes 5 and 6 as more relevant; node 5 is the more relevant of the two and is selected.
    std::vector<SelectionNode> nodes = {
        {1, 500, 10}, {2, 450, 20}, {3, 350, 5}, {4, 300, 3}, {5, 200, 9}, {6, 150, 7}, {7, 100, 2},
    };
    SelectionGraph g(nodes);
    EXPECT_EQ(g.node(3).object, 4u);  // next after node 3 by cost
    EXPECT_EQ(pointedObjects(g, 3), (std::vector<std::uint32_t>{5, 6}));
    SelectionResult r = g.select(400.0);
    const std::vector<SelectionStep> expected = {
        {Action::Dropped, 1}, {Action::Dropped, 2}, {Action::PassedOver, 3}, {Action::Selected, 5},
        // 200 left: 3 (350) and 4 (300) no longer fit; 6 (150) fits and nothing cheaper is more
        // relevant; then 50 left and 7 (100) is dropped.
        {Action::Dropped, 3}, {Action::Dropped, 4}, {Action::Selected, 6}, {Action::Dropped, 7},
    };
    ASSERT_EQ(r.steps.size(), expected.size());
    for (std::size_t i = 0; i < expected.size(); ++i) {
        EXPECT_EQ(r.steps[i].action, expected[i].action) << i;
        EXPECT_EQ(r.steps[i].object, expected[i].object) << i;
    }
    EXPECT_EQ(r.selected, (std::vector<std::uint32_t>{5, 6}));
}

std::vector<SelectionNode> randomNodes(std::mt19937& rng, int n) {
    std::uniform_real_distribution<double> cost(1.0, 1000.0), rel(0.0, 100.0);
    std::uniform_int_distribution<int> coin(0, 4);
    std::vector<SelectionNode> nodes;
    for (int i = 0; i < n; ++i) {
        // Some equal costs, to exercise ties.
        double c = coin(rng) == 0 && !nodes.empty() ? nodes.back().cost : cost(rng);
        nodes.push_back({static_cast<std::uint32_t>(i), c, rel(rng)});
    }
    return nodes;
}

TEST(SelectionGraph, RandomGraphsNeverExceedTheBudgetAndSelectEachObjectOnce) {
    std::mt19937 rng(12345);
    for (int trial = 0; trial < 2000; ++trial) {
        auto nodes = randomNodes(rng, 1 + trial % 40);
        SelectionGraph g(nodes);
        for (std::size_t i = 1; i < g.size(); ++i) ASSERT_GE(g.node(i - 1).cost, g.node(i).cost);
        double budget = std::uniform_real_distribution<double>(0.0, 8000.0)(rng);
        SelectionResult r = g.select(budget);
        double sum = 0.0;
        for (auto o : r.selected) sum += nodes[o].cost;
        ASSERT_LE(sum, budget) << trial;
        ASSERT_DOUBLE_EQ(sum, r.costUsed);
        ASSERT_EQ(std::set<std::uint32_t>(r.selected.begin(), r.selected.end()).size(), r.selected.size());
    }
}

TEST(SelectionGraph, UnlimitedBudgetSelectsEveryObject) {
    std::mt19937 rng(7);
    for (int trial = 0; trial < 200; ++trial) {
        auto nodes = randomNodes(rng, 1 + trial % 30);
        SelectionResult r = SelectionGraph(nodes).select(std::numeric_limits<double>::infinity());
        EXPECT_EQ(r.selected.size(), nodes.size());
    }
}

TEST(Heuristic, ScoresFollowEquations1To3) {
    ObjectObservation o;
    o.visiblePixels = 1000;
    o.boundsCenterNdc = {0.0f, 0.0f};
    o.distance = 4.0;
    o.staticRelevance = 2.0;
    o.estimatedCost = 1.5;
    ObjectScore s = scoreObject(o, 3, 50.0);
    EXPECT_DOUBLE_EQ(s.P, 1.0);           // centred
    EXPECT_DOUBLE_EQ(s.V, 1000.0 / 4.0);  // eq. (1)
    EXPECT_DOUBLE_EQ(s.Q, 3.0);           // lights only
    EXPECT_DOUBLE_EQ(s.C, 1000.0 * 3.0 * 1.5);
    EXPECT_DOUBLE_EQ(s.R, 250.0 * 2.0);
    o.boundsCenterNdc = {0.6f, 0.8f};  // |bb| = 1: off-centre by the full half-screen
    o.reflective = true;
    o.refractive = true;
    o.selectedLastFrame = true;
    s = scoreObject(o, 3, 50.0);
    EXPECT_NEAR(s.P, 0.01, 1e-7);
    EXPECT_DOUBLE_EQ(s.Q, 3.0 + (3 + 1) + (3 + 4));
    EXPECT_NEAR(s.R, (50.0 + 1000.0 * s.P / 4.0) * 2.0, 1e-9);  // eq. (3)
    o.boundsCenterNdc = {0.3f, 0.4f};  // |bb| = 0.5
    EXPECT_NEAR(scoreObject(o, 3, 0.0).P, 0.5 * 0.99 + 0.01, 1e-7);
}

// Selections over two frames with small motion (every A and D changes by a few per cent), with
// and without weight on last frame's selection: returns the mean fraction of frame 1's selection
// kept in frame 2.
double keptFraction(double importance) {
    std::mt19937 rng(99);
    std::uniform_real_distribution<double> pixels(100, 20000), dist(1, 30), jitter(0.95, 1.05), ndc(-1, 1);
    double kept = 0.0;
    const int trials = 300;
    for (int t = 0; t < trials; ++t) {
        std::vector<ObjectObservation> objs(20);
        for (std::uint32_t i = 0; i < objs.size(); ++i) {
            objs[i].object = i;
            objs[i].visiblePixels = pixels(rng);
            objs[i].distance = dist(rng);
            objs[i].boundsCenterNdc = {static_cast<float>(ndc(rng)), static_cast<float>(ndc(rng))};
            objs[i].reflective = i % 3 == 0;
            objs[i].refractive = i % 4 == 0;
        }
        auto select = [&](const std::vector<ObjectObservation>& os) {
            std::vector<SelectionNode> nodes;
            for (const auto& o : os) {
                ObjectScore s = scoreObject(o, 2, importance);
                nodes.push_back({o.object, s.C, s.R});
            }
            return SelectionGraph(nodes).select(400000.0).selected;
        };
        auto first = select(objs);
        std::set<std::uint32_t> chosen(first.begin(), first.end());
        for (auto& o : objs) {
            o.visiblePixels *= jitter(rng);
            o.distance *= jitter(rng);
            o.selectedLastFrame = chosen.count(o.object) > 0;
        }
        auto second = select(objs);
        std::size_t same = 0;
        for (auto o : second) same += chosen.count(o);
        kept += first.empty() ? 1.0 : static_cast<double>(same) / static_cast<double>(first.size());
    }
    return kept / trials;
}

TEST(Heuristic, HigherImportanceOfLastSelectionKeepsItUnderSmallMotion) {
    const double without = keptFraction(0.0), with = keptFraction(1e6);
    EXPECT_GT(with, without);
    EXPECT_GT(with, 0.9);
}

}  // namespace
}  // namespace hybridlab
