#pragma once
// `target_ms`: a frame-time target in place of Walewski's abstract cost budget T (beyond the paper,
// which tuned T by hand to stay above 25 fps, §4-5). The ray-tracing stage's time is close to
// proportional to the selected cost C (eq. 2 counts rays), so a running estimate of milliseconds
// per unit of cost turns the time left after the other stages into T for the next frame.
namespace hybridlab {

class FrameTimeBudget {
public:
    explicit FrameTimeBudget(double targetMilliseconds) : target_(targetMilliseconds) {}

    double targetMilliseconds() const { return target_; }
    // T for the next frame: the time the target leaves after the other stages, in units of cost.
    double budget() const;
    // The frame time expected when `cost` is selected.
    double predictedMilliseconds(double cost) const { return otherMilliseconds_ + millisecondsPerCost_ * cost; }

    // Learns from a finished frame: the cost selected, the ray-tracing stage's time and the time of
    // everything else (rasterization, heuristic, blending).
    void observe(double costUsed, double rayTracingMilliseconds, double otherMilliseconds);

private:
    double target_;
    // Before the first frame: about 4.5 Mrays/s incoherent on this class of machine (Embree, 2
    // cores), and C counts rays; the first frames correct it.
    double millisecondsPerCost_ = 1.0 / 4500.0;
    double otherMilliseconds_ = 0.0;
    // Exponentially decaying sums (the ratio of sums weights frames by their cost, so that frames
    // with little to trace, whose time is mostly fixed overhead, do not dominate).
    double weightedMilliseconds_ = 0.0, weightedCost_ = 0.0;
    bool observed_ = false;
};

}  // namespace hybridlab
