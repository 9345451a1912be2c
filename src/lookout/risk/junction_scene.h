#pragma once

// The risk issue's benchmark input: `count` road users round a junction (cars, cyclists and
// pedestrians in turn) with positions, speeds and track covariances drawn from `seed`, so that
// every run of `bench/risk_bench.cc` and `lookout bench` times the same scene.

#include <cstdint>
#include <vector>

#include "lookout/risk/risk_assessment.h"

namespace lookout::risk {

std::vector<ObjectInput> JunctionRoadUsers(int count, std::uint64_t seed);

}  // namespace lookout::risk
