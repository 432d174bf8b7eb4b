#pragma once
// `hybridlab run --scale S`: an experiment rendered at a fraction of its configured size, for a
// desk without a GPU (a 1280x720 paper config on lavapipe's rays takes a day). Every configured
// resolution is multiplied by S and rounded to even pixels, at least 16 a side; nothing else is
// scaled (cost budgets and other pixel-count-dependent parameters stay as configured, so a scaled
// run's budget covers a larger share of its pixels). The scale is recorded in experiment.json as
// "resolution_scale", and `--resume` of a set rendered at another scale is refused.
#include <string>

#include "experiments/runner/experiment_config.h"

namespace hybridlab {

// "--scale TEXT" as a number in (0, 1]; InputError naming the text otherwise.
double parseResolutionScale(const std::string& text);

// 0.25, 1: as few digits as give the value back, so that a message's --scale resumes the set.
std::string formatScale(double scale);

// One configured side at `scale`: rounded to an even count, at least 16 (or the side itself when
// it is smaller), never more than the side.
int scaledSide(int side, double scale);

// Every [[scenes]] resolution of `config` at `scale`, and config.resolutionScale set to it.
void scaleResolutions(ExperimentConfig& config, double scale);

}  // namespace hybridlab
