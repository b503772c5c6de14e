// build --json: a material's report as JSON, each output with its cache use and check.
#pragma once

#include <nlohmann/json.hpp>

#include "heightpack/bake/build/build_report.hpp"

namespace heightpack::cli {

// The report of one material's build; the output folder and material.json null for a check-only run.
nlohmann::json buildReportJson(const BuildReport& report, double threshold, bool checkOnly);

}  // namespace heightpack::cli
