// Internal: how the build words what went wrong in a step.
#pragma once

#include <functional>
#include <string>

#include "heightpack/bake/check_job.hpp"

#include "build_plan.hpp"

namespace heightpack::detail {

// The first failing edge of a check, in words.
std::string describeFailure(const CheckReport& r);

// Runs body; an exception it throws becomes the step's error (Internal).
void guarded(Step& s, const std::function<void()>& body);

// A source's error names the source file; the hint gains which asset of which manifest read it.
Error inAsset(Error e, const Step& s, const std::string& manifestPath);

// The check failure of a step whose source must tile and does not (report.check says how), with the
// tile command that fixes it.
Error tileFailure(const Step& s, const std::string& manifestPath);

}  // namespace heightpack::detail
